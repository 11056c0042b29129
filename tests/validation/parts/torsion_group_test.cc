// derive() and describe() of the parts torsion, harmonics, delta_vs_k and norton_fig13_8 on small fixed tables of
// their own, read the way `report merge` reads a report's CSV files (csv.h: typed rows through each table's schema).
// Every expected number is worked out by hand from the rows below.

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "crankcheck/validation/csv.h"
#include "crankcheck/validation/parts.h"
#include "part_fixture.h"

namespace crankcheck::validation {
namespace {

using testing::findParagraph;
using testing::readTable;

// Row `row`'s cell in column `column` of `t` as a number (fails the test for any other cell).
double getNumber(const Table& t, size_t row, const std::string& column) {
  const Cell cell = t.cell(row, columnOf(t, column));
  const double* x = std::get_if<double>(&cell);
  EXPECT_NE(x, nullptr) << column;
  return x ? *x : 0.0;
}

// Row `row`'s field in column `column` of `t` as the CSV writes it.
std::string getField(const Table& t, size_t row, const std::string& column) {
  return formatCell(t.cell(row, columnOf(t, column)));
}

// ---- torsion ----

// One scene "s", three speeds. The exact curve peaks at 2000 rpm (1, 3, 2 mrad): the parabola through the three points
// has its vertex at 2000 + 500 (1 - 2) / (1 - 6 + 2) = 2166.67 rpm. Order 6 rises there (2 mrad against its
// neighbours' 0.5: +1.5), order 2 does not (1, 1, 1), so the peak is order 6 at 6 x 2166.67 / 60 = 216.67 Hz, nearest
// mode 2 (250 Hz; mode 1 is at 100 Hz), whose order-6 critical speed is 250 x 60 / 6 = 2500 rpm. Holzer's curve (1, 2,
// 3 mrad) rises throughout: no peak, so Holzer misses the exact one.
TableSet makeTorsionTables() {
  TableSet tables;
  tables.emplace("torsion", readTable("torsion",
                                      "scene,speed_rpm [rpm],holzer [rad],holzer_order24 [rad],exact [rad],difference [-],"
                                      "worst_difference [-],section,worst_section,error_bound [rad]\n"
                                      "s,1000,0.001,0.00101,0.001,0,0.005,a-b,a-b,1e-10\n"
                                      "s,2000,0.002,0.002,0.003,0.5,0.5,a-b,a-b,1e-10\n"
                                      "s,3000,0.003,0.003,0.002,-0.333,-0.2,a-b,b-c,1e-10\n"));
  tables.emplace("torsion_orders", readTable("torsion_orders",
                                             "scene,speed_rpm [rpm],order [-],holzer [rad],exact [rad]\n"
                                             "s,1000,2,0.001,0.001\n"
                                             "s,1000,6,0.0005,0.0005\n"
                                             "s,2000,2,0.001,0.001\n"
                                             "s,2000,6,0.0005,0.002\n"
                                             "s,3000,2,0.001,0.001\n"
                                             "s,3000,6,0.0005,0.0005\n"));
  tables.emplace("torsion_modes", readTable("torsion_modes",
                                            "scene,mode [-],holzer_hz [Hz],min_hz [Hz],max_hz [Hz],firings_per_turn [-]\n"
                                            "s,1,100,90,110,2\n"
                                            "s,2,250,240,260,2\n"));
  tables.emplace("torsion_inertia",
                 readTable("torsion_inertia",
                           "scene,throw [-],exact_inertia [kg m^2],min_inertia [kg m^2],max_inertia [kg m^2],"
                           "half_reciprocating [kg m^2],half_reciprocating_error [-],second_order [kg m^2],"
                           "second_order_error [-]\n"
                           "s,0,0.01,0.009,0.012,0.0099,-0.01,0.01,0\n"));
  tables.emplace("torsion_ratio", readTable("torsion_ratio",
                                            "scene,piston_mass_factor [-],ratio [-],order [-],speed_rpm [rpm],holzer [rad],"
                                            "exact [rad],worst_difference [-]\n"
                                            "s,1,0.5,6,1000,0.001,0.00102,0.02\n"
                                            "s,4,2,6,800,0.001,0.0012,0.2\n"
                                            "s,16,8,6,600,0.001,,\n"));
  tables.emplace("torsion_cost", readTable("torsion_cost",
                                           "scene,route,speed_rpm [rpm],seconds [s]\n"
                                           "s,holzer,1000,0.1\n"
                                           "s,holzer,2000,0.3\n"));
  return tables;
}

TEST(TorsionGroupTest, TorsionFindsTheResonancesAndReadsHolzersError) {
  TableSet tables = makeTorsionTables();
  const Part& part = findPart("torsion");
  part.derive(tables);
  ASSERT_TRUE(tables.count("torsion_resonances"));
  const Table& peaks = tables.at("torsion_resonances");
  ASSERT_EQ(peaks.size(), 1u);
  EXPECT_EQ(getField(peaks, 0, "scene"), "s");
  EXPECT_EQ(getField(peaks, 0, "route"), "exact");
  EXPECT_EQ(getNumber(peaks, 0, "order"), 6.0);
  EXPECT_EQ(getNumber(peaks, 0, "mode"), 2.0);
  // The parabola's vertex from three rounded products: a few ulps of 2000 rpm (1e-9 rpm is 1e3 of them).
  EXPECT_NEAR(getNumber(peaks, 0, "speed_rpm"), 2000.0 + 500.0 / 3.0, 1e-9);
  EXPECT_NEAR(getNumber(peaks, 0, "frequency_hz"), 6.0 * (2000.0 + 500.0 / 3.0) / 60.0, 1e-9);
  EXPECT_NEAR(getNumber(peaks, 0, "critical_rpm"), 2500.0, 1e-9);
  EXPECT_EQ(getNumber(peaks, 0, "twist"), 0.003);  // the grid point's value, copied
  const ReportPart d = part.describe(tables);
  EXPECT_EQ(d.heading, "17. Torsional vibration: Holzer's constant inertia against the exact crank train");
  // |worst difference| 0.005 <= 1 % at 1000 rpm; 0.5 > 10 % at 2000; 0.2 > 10 % at 3000. The cut at 24: 1 % at 1000.
  EXPECT_EQ(findParagraph(d, "3 speeds"),
            "s, 3 speeds from 1000 to 3000 rpm: Holzer's peak-to-peak twist (every order summed) is within 1 % of the exact "
            "steady state's on every section at 1 of them and off by more than 10 % on some section at 2; at worst 50 % "
            "(a-b, 2000 rpm). The textbook's sum cut at order 24 differs from the converged sum by up to 1 % (at 1000 rpm).");
  // 2166.67 / 2500 - 1 = -13.3 %.
  EXPECT_NE(findParagraph(d, "s: the exact steady state peaks at order 6 at 2167 rpm (mode 2; Holzer's critical speed 2500 "
                             "rpm, -13.3 %), where Holzer's sum has no peak within 5 %").size(), 0u);
  // Mode 1: 100 Hz, band 90 .. 110 Hz: 20 %.
  EXPECT_NE(findParagraph(d, "s: mode 1 is at 100 Hz with Holzer's J_eq; with every throw at its lightest and at its "
                             "heaviest over a turn it would be at 110 and 90 Hz: a spread of 20 %").size(), 0u);
  // The ratio sweep: 2 % at 0.5, 20 % at 2 (the first beyond 10 %), no periodic state at 8.
  EXPECT_NE(findParagraph(d, "s, its piston mass scaled so that the reciprocating inertia runs from 0.5 to 8 times the "
                             "rotating one, at Holzer's critical speed of mode 1 and order 6: Holzer's worst section is "
                             "off by 2 % at 0.5, 20 % at 2, no periodic state at 8. The constant-inertia model is off by "
                             "more than 10 % from a ratio of 2 on.").size(), 0u);
  // (0.1 + 0.3) / 2 = 0.2 s.
  EXPECT_NE(findParagraph(d, "holzer 0.2 s (2 points)").size(), 0u);
  // The tables: the inertias to 4 digits, then the peaks.
  const ReportBlock* inertia = nullptr;
  const ReportBlock* resonances = nullptr;
  for (const ReportBlock& b : d.blocks)
    if (b.kind == ReportBlock::kTable) (inertia ? resonances : inertia) = &b;
  ASSERT_NE(inertia, nullptr);
  ASSERT_EQ(inertia->rows.size(), 1u);
  EXPECT_EQ(inertia->rows[0], (std::vector<std::string>{"s", "0", "0.01", "0.009", "0.012", "0.0099", "-0.01", "0.01", "0"}));
  ASSERT_NE(resonances, nullptr);
  ASSERT_EQ(resonances->rows.size(), 1u);
  EXPECT_EQ(resonances->rows[0], (std::vector<std::string>{"s", "exact", "6", "2", "2167", "216.7", "2500", "0.003"}));
}

// A peak whose rising order is near no mode: mode and critical speed empty, said so in the sentence; Holzer's peak at
// the same order within 5 % of the speed is a match.
TEST(TorsionGroupTest, TorsionSaysWhichPeaksHolzerMatchesAndWhichHaveNoMode) {
  TableSet tables = makeTorsionTables();
  tables.insert_or_assign("torsion_resonances",
                          readTable("torsion_resonances",
                                    "scene,route,order [-],mode [-],speed_rpm [rpm],frequency_hz [Hz],critical_rpm [rpm],"
                                    "twist [rad]\n"
                                    "s,exact,6,2,2000,200,2500,0.003\n"
                                    "s,exact,1.5,,1200,30,,0.001\n"
                                    "s,holzer,6,2,2090,209,2500,0.003\n"));
  const ReportPart d = findPart("torsion").describe(tables);
  // 2090 / 2000 - 1 = 4.5 % < 5 %: matched; 2000 / 2500 - 1 = -20 %. Order 1.5 has no Holzer peak: missed.
  EXPECT_NE(findParagraph(d, "s: the exact steady state peaks at order 6 at 2000 rpm (mode 2; Holzer's critical speed 2500 "
                             "rpm, -20 %), where Holzer's sum peaks too (within 5 %); and at order 1.5 at 1200 rpm (no "
                             "mode near its frequency), where Holzer's sum has no peak within 5 %").size(), 0u);
}

// Each engine's own train: the largest |difference| per engine, how it was run (a gated engine's accuracy, a soft
// one's fixed step as a fraction of a cycle), and the mean cost per route.
TEST(TorsionGroupTest, TorsionReadsTheEnginesTrainsAndTheirCost) {
  TableSet tables = makeTorsionTables();
  tables.insert_or_assign("torsion_engines",
                          readTable("torsion_engines",
                                    "scene,engine,speed_rpm [rpm],section,peak_to_peak [rad],exact [rad],difference [-],"
                                    "cycles [-],accuracy [-],periodicity [-]\n"
                                    "s,simbody,3000,a-b,0.001,0.001,2e-06,4,1e-07,0.0001\n"
                                    "s,simbody,3000,b-c,0.002,0.002,-5e-06,4,1e-07,0.0001\n"
                                    "s,mujoco-soft,3000,a-b,0.001,0.001,0.12,6,0.0009765625,0.0001\n"));
  tables.insert_or_assign("torsion_cost", readTable("torsion_cost",
                                                    "scene,route,speed_rpm [rpm],seconds [s]\n"
                                                    "s,holzer,1000,0.1\n"
                                                    "s,holzer,2000,0.3\n"
                                                    "s,simbody,3000,2.5\n"));
  const ReportPart d = findPart("torsion").describe(tables);
  EXPECT_EQ(findParagraph(d, "simbody's own"),
            "simbody's own elastic train agrees with the analytic steady state's peak-to-peak twists to 5e-06 of the twist "
            "scale on s at 3000 rpm (accuracy 1e-07, run until the cycle-to-cycle change is below 0.0001 of the twist).");
  // 0.0009765625 = 1/1024.
  EXPECT_EQ(findParagraph(d, "mujoco-soft's own"),
            "mujoco-soft's own elastic train (a soft solver: measured, not gated) differs from the analytic steady state's "
            "peak-to-peak twists by up to 0.12 of the twist scale on s at 3000 rpm (a fixed step of 1/1024 of a cycle, run "
            "until the cycle-to-cycle change is below 0.0001 of the twist).");
  EXPECT_EQ(findParagraph(d, "Cost of a speed point"),
            "Cost of a speed point in this campaign (mean wall time, other work beside it): holzer 0.2 s (2 points), "
            "simbody 2.5 s (1 point).");
}

// A route refused (its task's line in the notes, tagged with the part): the part's tables out, and a note that says
// so. A note of the campaign's own, even one that names torsion, leaves the part in.
TEST(TorsionGroupTest, TorsionIsLeftOutWhenARouteWasRefused) {
  const Part& part = findPart("torsion");
  auto makeNotes = [](const std::vector<std::string>& lines) {
    std::vector<NoteRow> rows;
    for (const std::string& line : lines) rows.push_back({line});
    return kNotesTable.table(std::move(rows));
  };
  TableSet kept = makeTorsionTables();
  kept.emplace("notes", makeNotes({"No scene for torsion was slow (a note that names the part)."}));
  part.derive(kept);
  EXPECT_TRUE(kept.count("torsion_resonances"));
  EXPECT_EQ(getRows(kept, kNotesTable).size(), 1u);
  EXPECT_FALSE(part.describe(kept).heading.empty());

  TableSet refused = makeTorsionTables();
  const std::string tag = "Part " + std::to_string(part.number()) + " (torsion)";
  refused.emplace("notes", makeNotes({"Only the report parts torsion were run (validate --parts).",
                                      tag + ": s at 3000 rpm not computed: twisted too far"}));
  part.derive(refused);
  for (const std::string& name : part.tables()) EXPECT_FALSE(refused.count(name)) << name;
  const std::vector<NoteRow>& notes = getRows(refused, kNotesTable);
  ASSERT_EQ(notes.size(), 3u);
  EXPECT_EQ(notes[2].note, tag + " is left out: the routes these notes name could not be computed, and a sweep "
                         "with holes is not drawn. crankcheck torsion on each scene shows the rest.");
  EXPECT_TRUE(part.describe(refused).heading.empty());
}

// The part needs its sweep, modes and inertias, and at least one speed of the sweep.
TEST(TorsionGroupTest, TorsionIsLeftOutWithoutItsTables) {
  const Part& part = findPart("torsion");
  for (const char* missing : {"torsion", "torsion_modes", "torsion_inertia"}) {
    TableSet tables = makeTorsionTables();
    tables.erase(missing);
    EXPECT_TRUE(part.describe(tables).heading.empty()) << missing;
  }
  TableSet empty = makeTorsionTables();
  empty.insert_or_assign("torsion", readTable("torsion",
                                              "scene,speed_rpm [rpm],holzer [rad],holzer_order24 [rad],exact [rad],"
                                              "difference [-],worst_difference [-],section,worst_section,error_bound [rad]\n"));
  EXPECT_TRUE(part.describe(empty).heading.empty());
  // derive needs the sweep, its orders and the modes: without one of them no resonances table.
  for (const char* missing : {"torsion", "torsion_orders", "torsion_modes"}) {
    TableSet tables = makeTorsionTables();
    tables.erase(missing);
    part.derive(tables);
    EXPECT_FALSE(tables.count("torsion_resonances")) << missing;
  }
}

// ---- harmonics, delta_vs_k, norton_fig13_8: each its figure with a caption ----

// harmonics' columns: one amplitude per reference engine of this build's registry (simbody, then mujoco), and the
// paper's claim as text, "1", "0" or empty (the paper says nothing). The CSV reads back to the same text.
TEST(TorsionGroupTest, HarmonicsReadsEveryReferenceEnginesColumnAndThePapersClaim) {
  const std::string csv =
      "cycle,k [-],n [-],analytic_amplitude [N m],paper_nonzero,simbody_amplitude [N m],mujoco_amplitude [N m]\n"
      "two-stroke,1,1,0.38,1,0.38000000000000006,0.38\n"
      "two-stroke,2,1,0,0,1e-17,0\n"
      "two-stroke,2,13,0,,2e-17,3e-17\n";
  const Table t = readTable("harmonics", csv);
  ASSERT_NE(t.schema(), nullptr);
  EXPECT_EQ(formatCsv(t), csv);
  EXPECT_EQ(getField(t, 1, "paper_nonzero"), "0");
  EXPECT_EQ(getField(t, 2, "paper_nonzero"), "");
  EXPECT_EQ(getNumber(t, 2, "mujoco_amplitude"), 3e-17);
  // Another engine set than this build's is refused, naming the file.
  EXPECT_THROW(readTable("harmonics", "cycle,k [-],n [-],analytic_amplitude [N m],paper_nonzero,simbody_amplitude [N m]\n"),
               std::runtime_error);

  const Part& part = findPart("harmonics");
  EXPECT_TRUE(part.describe({}).heading.empty());
  const ReportPart d = part.describe({{"harmonics", t}});
  EXPECT_EQ(d.heading, "3. Harmonics of Q");
  EXPECT_EQ(d.caption.rfind("Harmonics of Q by a DFT of simbody's Q(phi) (64 angles, lambda = 0.4", 0), 0u) << d.caption;
}

// delta_vs_k: NaN where the engine is too slow to turn over against gravity; the CSV reads back to the same text.
TEST(TorsionGroupTest, DeltaVsKIsItsFigure) {
  const std::string csv =
      "cycle,k [-],speed_rpm [rpm],delta_gravity [-],delta_no_gravity [-],delta_due_to_gravity [-]\n"
      "four-stroke,1,60,nan,nan,nan\n"
      "four-stroke,1,300,0.0065,0.0036,0.0029\n";
  const Table t = readTable("delta_vs_k", csv);
  ASSERT_NE(t.schema(), nullptr);
  EXPECT_EQ(formatCsv(t), csv);
  EXPECT_EQ(getNumber(t, 1, "k"), 1.0);
  const Part& part = findPart("delta_vs_k");
  EXPECT_TRUE(part.describe({}).heading.empty());
  const ReportPart d = part.describe({{"delta_vs_k", t}});
  EXPECT_EQ(d.heading, "6. Speed fluctuation due to gravity in the free run");
  EXPECT_EQ(d.caption.rfind("The free run (released at phi = 0, no drive, no load", 0), 0u) << d.caption;
  EXPECT_TRUE(d.paragraphs.empty());
}

TEST(TorsionGroupTest, NortonFigureIsItsFigure) {
  const std::string csv =
      "crank_angle_deg [deg],x_exact [m],x_two_term [m],v_exact [m/s],v_two_term [m/s],a_exact [m/s^2],a_two_term [m/s^2]\n"
      "0,0.188,0.188,0,0,-5502.4746192004395,-5502.4746192004395\n"
      "1,0.18799150887726873,0.1879915088902736,-0.30566780251149256,-0.3056668662477127,-5501.112125332381,"
      "-5501.061576679096\n";
  const Table t = readTable("norton_fig13_8", csv);
  ASSERT_NE(t.schema(), nullptr);
  EXPECT_EQ(formatCsv(t), csv);
  const Part& part = findPart("norton_fig13_8");
  EXPECT_TRUE(part.describe({}).heading.empty());
  const ReportPart d = part.describe({{"norton_fig13_8", t}});
  EXPECT_EQ(d.heading, "5. Piston motion (after Norton fig. 13-8)");
  EXPECT_EQ(d.caption, "Piston position, velocity and acceleration over two revolutions, exact and Norton's two-term "
                       "(13.3c-e), for the base scene");
}

}  // namespace
}  // namespace crankcheck::validation
