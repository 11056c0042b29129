#include "crankcheck/validation/report.h"

#include <algorithm>
#include <chrono>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fstream>
#include <map>
#include <set>
#include <tuple>
#include <nlohmann/json.hpp>
#include <sstream>
#include <exception>
#include <thread>
#include <mutex>
#include <stdexcept>

#include "crankcheck/validation/report_format.h"
#include "crankcheck/validation/csv.h"
#include "crankcheck/validation/table_schemas.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/errors.h"
#include "crankcheck/validation/install_paths.h"
#include "crankcheck/validation/verdict.h"
#include "crankcheck/validation/report_document.h"
#include "crankcheck/validation/output_folder.h"
#include "crankcheck/validation/parts.h"
#include "crankcheck/validation/process.h"


namespace crankcheck::validation {
namespace fs = std::filesystem;

std::string calcChecksum(std::string_view bytes) {
  std::uint64_t h = 0xcbf29ce484222325ull;  // FNV-1a 64: offset basis, then xor and multiply by the prime per byte
  for (const unsigned char c : bytes) h = (h ^ c) * 0x100000001b3ull;
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
  return hex;
}

namespace {

}  // namespace

std::vector<DataFileRecord> writeTables(const TableSet& tables, const fs::path& dir) {
  std::error_code ec;
  if (!fs::create_directory(dir / "data", ec) && ec)
    throw EnvironmentError(quotePath(dir / "data") + ": cannot create the folder: " + ec.message());
  std::vector<DataFileRecord> records;
  for (const auto& [name, table] : tables) {
    const std::string text = formatCsv(table);
    const std::string header = text.substr(0, text.find('\n'));
    writeNewFile(dir / "data" / (name + ".csv"), text);
    records.push_back({"data/" + name + ".csv", header, table.size(), calcChecksum(text)});
  }
  return records;
}

namespace {

// The file's bytes. @throws EnvironmentError when it cannot be read.
std::string readBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw EnvironmentError(quotePath(path) + ": cannot read: " + std::strerror(errno));
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

TableSet readTables(const fs::path& dir) {
  TableSet tables;
  if (!fs::is_directory(dir / "data"))
    throw std::runtime_error(quotePath(dir) + ": no data/ folder (not a crankcheck report or shard)");
  for (const auto& entry : fs::directory_iterator(dir / "data")) {
    if (entry.path().extension() != ".csv") continue;
    const std::string source = quotePath(entry.path());
    const std::string name = entry.path().stem().string();
    tables[name] = parseTable(name, parseCsv(readBytes(entry.path()), source), source, findTableSchema(name));
  }
  return tables;
}

namespace {

// ------------------------------------------------------------------------------------------------------------
// A small document model rendered both as Markdown and as HTML.

struct Block {
  enum Kind { kHeading, kParagraph, kTable, kFigure } kind = kParagraph;
  std::string text = {};                       // heading / paragraph / caption
  std::vector<std::string> header = {};        // table
  std::vector<std::vector<std::string>> rows = {};
  std::string name = {};                       // figure stem (name.png, name.svg, data/name.csv); "#" on the title
  std::string id = {};                         // a heading's anchor (a part's key); empty: made of its text
};

// The blocks as a ReportDocument: index.md as written, index.html rendered from it by cmark-gfm; the texts of
// `as_written` (the scenes' names) shown as written.
ReportDocument toDocument(const std::vector<Block>& blocks, const std::string& title, std::vector<std::string> as_written) {
  ReportDocument doc(title);
  doc.showAsWritten(std::move(as_written));
  for (const Block& b : blocks) {
    switch (b.kind) {
      case Block::kHeading:
        if (b.name != "#")  // "#": the title
          doc.addHeading(b.name.empty() ? 2 : static_cast<int>(b.name.size()), b.text, b.id);
        break;
      case Block::kParagraph: doc.addParagraph(b.text); break;
      case Block::kTable: doc.addTable(b.header, b.rows); break;
      case Block::kFigure: doc.addFigure(b.name, b.text); break;
    }
  }
  return doc;
}

std::string today() {
  const std::time_t now = std::time(nullptr);
  char buffer[32];
  std::strftime(buffer, sizeof buffer, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
  return buffer;
}

}  // namespace

void renderReport(const TableSet& input, const ReportInfo& info, const fs::path& dir) {
  TableSet tables = input;
  sortTables(tables);  // first: the derived tables then do not depend on the order tasks ran in
  for (const Part* part : listParts()) part->derive(tables);
  sortTables(tables);
  writeTables(tables, dir);

  // The figures dealt out in turn to up to info.jobs gnuplots at a time, each drawing its share one after the other
  // (drawFigures; each figure writes only its own NAME.svg and NAME.png).
  std::vector<std::string> to_draw;
  for (const Part* part : listParts())
    for (const std::string& figure : part->figures())
      if (tables.count(figure) && tables.at(figure).size() > 0) to_draw.push_back(figure);  // a figure of no row: none
  const size_t drawer_count = std::min(static_cast<size_t>(std::max(info.jobs, 1)), to_draw.size());
  std::vector<std::vector<std::string>> shares(drawer_count);
  for (size_t i = 0; i < to_draw.size(); ++i) shares[i % drawer_count].push_back(to_draw[i]);
  std::mutex error_mutex;
  std::exception_ptr error;
  auto drawer = [&](size_t j) {
    try {
      drawFigures(shares[j], dir);
    } catch (...) {
      std::lock_guard<std::mutex> lock(error_mutex);
      if (!error) error = std::current_exception();
    }
  };
  std::vector<std::thread> drawers;
  for (size_t j = 1; j < drawer_count; ++j) drawers.emplace_back(drawer, j);
  if (drawer_count > 0) drawer(0);
  for (std::thread& t : drawers) t.join();
  if (error) std::rethrow_exception(error);

  std::vector<Block> doc;
  doc.push_back({Block::kHeading, info.title, {}, {}, "#"});
  std::ostringstream meta;
  meta << "Generated " << today() << " by crankcheck " << getCrankcheckVersion() << " with " << joinEngineLibraries()
       << ", compiler " << __VERSION__ << ", " << info.gnuplot_version << ". Campaign: "
       << (info.quick ? "quick" : "full") << ", " << info.jobs << " job(s)" << (info.shards > 1 ? ", merged from " + std::to_string(info.shards) + " shards" : "")
       << (info.seconds > 0 ? ", " + shortNumber(info.seconds, 3) + " s" : "") << ".";
  doc.push_back({Block::kParagraph, meta.str()});

  // Every part (parts.h) in the registry's order, described by its own file: the verdict, the summary and the scenes
  // first, then the numbered parts; each its figure, sentences and table, or its blocks in order.
  for (const Part* part : listParts()) {
    const ReportPart described = part->describe(tables);
    if (described.heading.empty()) continue;
    doc.push_back({Block::kHeading, described.heading, {}, {}, {}, part->key()});  // #KEY: the same in every report
    if (described.blocks.empty()) {
      doc.push_back({Block::kFigure, described.caption, {}, {}, part->key()});
      for (const std::string& paragraph : described.paragraphs) doc.push_back({Block::kParagraph, paragraph});
      if (!described.header.empty()) doc.push_back({Block::kTable, "", described.header, described.rows});
    }
    for (const ReportBlock& b : described.blocks) {
      switch (b.kind) {
        case ReportBlock::kParagraph: doc.push_back({Block::kParagraph, b.text}); break;
        case ReportBlock::kTable: doc.push_back({Block::kTable, "", b.header, b.rows}); break;
        case ReportBlock::kFigure: doc.push_back({Block::kFigure, b.text, {}, {}, b.figure}); break;
        case ReportBlock::kHeading:
          doc.push_back({Block::kHeading, b.text, {}, {}, std::string(static_cast<size_t>(std::max(b.level, 3)), '#'), b.id});
          break;
      }
    }
  }

  const ReportDocument page = toDocument(doc, info.title, listSceneNames(tables));
  writeNewFile(dir / "index.md", page.toMarkdown());
  writeNewFile(dir / "index.html", page.toHtml());
}

namespace {

// shard.json's format: 2 added the campaign's identity (version, scenes' content) and the data files' records.
constexpr int kShardFormat = 4;  // 3: the parts run (validate --parts); 4: the engines that sat out

}  // namespace

void writeShardManifest(const ShardManifest& manifest, const fs::path& dir) {
  nlohmann::json scenes = nlohmann::json::array(), files = nlohmann::json::array();
  for (const ShardScene& scene : manifest.scenes) scenes.push_back({{"name", scene.name}, {"fnv1a64", scene.checksum}});
  for (const DataFileRecord& f : manifest.files)
    files.push_back({{"path", f.path}, {"header", f.header}, {"rows", f.rows}, {"fnv1a64", f.checksum}});
  nlohmann::json sat_out = nlohmann::json::array();
  for (const SatOut& s : manifest.sat_out) sat_out.push_back({{"engine", s.engine}, {"scene", s.scene}, {"reason", s.reason}});
  nlohmann::json j = {{"crankcheck_shard", kShardFormat}, {"version", manifest.version}, {"index", manifest.index},
                      {"count", manifest.count},          {"quick", manifest.quick},     {"scenes", scenes},
                      {"tasks", manifest.tasks},          {"files", files},              {"parts", manifest.parts},
                      {"sat_out", sat_out}};
  writeNewFile(dir / "shard.json", j.dump(2) + "\n");
}

namespace {

// A library's message without its tag: "[json.exception.parse_error.101] parse error at ..." -> "parse error at ...".
std::string withoutJsonTag(const std::string& what) {
  return what.rfind("[json.exception.", 0) == 0 && what.find("] ") != std::string::npos ? what.substr(what.find("] ") + 2)
                                                                                         : what;
}

// The values of shard.json, each named by its path in a message ("files[3].rows: must be a whole number >= 0 (got a
// string)"): a hand-edited or damaged record says where it is wrong, not what the JSON library tripped on.
struct ShardJsonReader {
  std::string file;  // quoted path of shard.json

  [[noreturn]] void fail(const std::string& path, const std::string& rule) const {
    throw std::runtime_error(file + ": malformed: " + path + ": " + rule);
  }
  const nlohmann::json& at(const nlohmann::json& object, const std::string& key, const std::string& path) const {
    if (!object.is_object()) fail(path.empty() ? "the record" : path, std::string("must be an object (got ") + object.type_name() + ")");
    const auto it = object.find(key);
    if (it == object.end()) fail(path.empty() ? key : path + "." + key, "missing");
    return *it;
  }
  std::string text(const nlohmann::json& object, const std::string& key, const std::string& path = "") const {
    const nlohmann::json& v = at(object, key, path);
    if (!v.is_string()) fail(path.empty() ? key : path + "." + key, std::string("must be a string (got ") + v.type_name() + ")");
    return v.get<std::string>();
  }
  long long whole(const nlohmann::json& object, const std::string& key, const std::string& path = "") const {
    const nlohmann::json& v = at(object, key, path);
    if (!v.is_number_integer() || v.get<long long>() < 0 || v.get<long long>() > (1LL << 40))
      fail(path.empty() ? key : path + "." + key, std::string("must be a whole number from 0 to 2^40 (got ") +
                                                      (v.is_number() ? escapeText(v.dump()) : v.type_name()) + ")");
    return v.get<long long>();
  }
  const nlohmann::json& list(const nlohmann::json& object, const std::string& key, const std::string& path = "") const {
    const nlohmann::json& v = at(object, key, path);
    if (!v.is_array()) fail(path.empty() ? key : path + "." + key, std::string("must be a list (got ") + v.type_name() + ")");
    return v;
  }
};

}  // namespace

ShardManifest readShardManifest(const fs::path& dir) {
  // A plain file inside the shard, as the folder rule asks: a link is not followed, a FIFO never waited on.
  std::error_code ec;
  const fs::file_status status = fs::symlink_status(dir / "shard.json", ec);
  if (fs::exists(status) && !fs::is_regular_file(status))
    throw std::runtime_error(quotePath(dir / "shard.json") + ": not a plain file (a link, a folder or a FIFO): not a "
                             "shard written by crankcheck validate --shard");
  std::ifstream in(dir / "shard.json");
  if (!in) throw std::runtime_error(quotePath(dir) + ": no shard.json (not a shard written by crankcheck validate --shard)");
  const ShardJsonReader r{quotePath(dir / "shard.json")};
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(r.file + ": malformed: not JSON (" + escapeText(withoutJsonTag(e.what())) + ")");
  }
  const long long format = r.whole(j, "crankcheck_shard");
  if (format != kShardFormat)
    throw std::runtime_error(r.file + ": a shard of format " + std::to_string(format) + ", written by another crankcheck; "
                             "this one (" + getCrankcheckVersion() + ") merges format " + std::to_string(kShardFormat) +
                             ": run the shard again");
  ShardManifest m;
  m.version = r.text(j, "version");
  m.index = static_cast<int>(std::min(r.whole(j, "index"), 1LL << 30));
  m.count = static_cast<int>(std::min(r.whole(j, "count"), 1LL << 30));
  const nlohmann::json& quick = r.at(j, "quick", "");
  if (!quick.is_boolean()) r.fail("quick", std::string("must be true or false (got ") + quick.type_name() + ")");
  m.quick = quick.get<bool>();
  const nlohmann::json& scenes = r.list(j, "scenes");
  for (size_t i = 0; i < scenes.size(); ++i) {
    const std::string path = "scenes[" + std::to_string(i) + "]";
    m.scenes.push_back({r.text(scenes[i], "name", path), r.text(scenes[i], "fnv1a64", path)});
  }
  m.tasks = static_cast<int>(std::min(r.whole(j, "tasks"), 1LL << 30));
  const nlohmann::json& parts = r.list(j, "parts");
  for (size_t i = 0; i < parts.size(); ++i) {
    if (!parts[i].is_string()) r.fail("parts[" + std::to_string(i) + "]", "must be a string");
    m.parts.push_back(parts[i].get<std::string>());
  }
  const nlohmann::json& sat_out = r.list(j, "sat_out");
  for (size_t i = 0; i < sat_out.size(); ++i) {
    const std::string path = "sat_out[" + std::to_string(i) + "]";
    m.sat_out.push_back({r.text(sat_out[i], "engine", path), r.text(sat_out[i], "scene", path),
                         r.text(sat_out[i], "reason", path)});
  }
  const nlohmann::json& files = r.list(j, "files");
  for (size_t i = 0; i < files.size(); ++i) {
    const std::string path = "files[" + std::to_string(i) + "]";
    m.files.push_back({r.text(files[i], "path", path), r.text(files[i], "header", path),
                       static_cast<size_t>(r.whole(files[i], "rows", path)), r.text(files[i], "fnv1a64", path)});
  }
  if (m.count < 1 || m.index >= m.count)
    throw std::runtime_error(r.file + ": malformed: shard " + std::to_string(m.index) + " of " + std::to_string(m.count));
  return m;
}

TableSet readShardTables(const fs::path& dir, const ShardManifest& manifest) {
  // Every file crankcheck-manifest.json lists (what the shard wrote, shard.json among them) must be there, each a plain
  // file inside the shard as the shard wrote it (its size and checksum).
  const fs::path listing = dir / kManifestName;
  std::set<std::string> listed;
  const FolderManifest folder = readFolderManifest(dir);
  if (folder.kind != "shard")
    throw std::runtime_error(quotePath(listing) + ": not a shard's manifest (kind " + quoteText(folder.kind) + ")");
  std::error_code ec;
  for (const ManifestFile& f : folder.files) {
    listed.insert(f.path);
    // A data file is checked below against shard.json's record, which says what differs (its header, its rows, its
    // content); every other file against the manifest's record.
    if (f.path.rfind("data/", 0) == 0 && fs::is_regular_file(fs::symlink_status(dir / f.path, ec)) &&
        !fs::is_symlink(fs::symlink_status(dir / "data", ec)))
      continue;
    if (!isAsRecorded(dir, f))
      throw std::runtime_error(quotePath(dir / f.path) + ": missing or changed, though the shard's " + kManifestName +
                               " lists it (a plain file of " + std::to_string(f.size) + " bytes, CRC-32 " + f.crc32 + ")");
  }
  // shard.json records exactly the data files listed, and data/ holds no other.
  std::set<std::string> recorded;
  for (const DataFileRecord& f : manifest.files) {
    const fs::path path(f.path);
    if (!recorded.insert(f.path).second || !listed.count(f.path) || path.parent_path() != "data" ||
        path.extension() != ".csv")
      throw std::runtime_error(quotePath(dir / "shard.json") + ": records " + quotePath(f.path) + ", which the shard's " +
                               kManifestName + " does not list as a data file");
  }
  for (const std::string& rel : listed)
    if (rel.rfind("data/", 0) == 0 && !recorded.count(rel))
      throw std::runtime_error(quotePath(dir / rel) + ": not listed in the shard's shard.json");
  if (!fs::is_directory(dir / "data")) throw std::runtime_error(quotePath(dir / "data") + ": missing");
  for (const auto& entry : fs::directory_iterator(dir / "data")) {
    const std::string rel = "data/" + entry.path().filename().string();
    if (!recorded.count(rel))
      throw std::runtime_error(quotePath(entry.path()) + ": not listed in the shard's manifest: not written by the shard");
  }
  // Each data file as the shard wrote it: its header, its rows, its checksum.
  TableSet tables;
  for (const DataFileRecord& f : manifest.files) {
    const fs::path path = dir / f.path;
    const std::string source = quotePath(path);
    const std::string text = readBytes(path);
    std::vector<std::vector<std::string>> records = parseCsv(text, source);
    const std::string header = text.substr(0, text.find('\n'));
    if (header != f.header)
      throw std::runtime_error(source + ": header " + quotePath(header.substr(0, 80)) + ", the shard wrote " +
                               quotePath(f.header.substr(0, 80)));
    const size_t rows = records.empty() ? 0 : records.size() - 1;
    if (rows != f.rows)
      throw std::runtime_error(source + ": " + std::to_string(rows) + " rows, the shard wrote " + std::to_string(f.rows));
    const std::string checksum = calcChecksum(text);
    if (checksum != f.checksum)
      throw std::runtime_error(source + ": not the content the shard wrote (FNV-1a 64 " + checksum + ", shard.json records " +
                               f.checksum + ")");
    const std::string name = fs::path(f.path).stem().string();
    tables[name] = parseTable(name, std::move(records), source, findTableSchema(name));
  }
  return tables;
}

std::string checkGnuplot() {
  if (findProgram("gnuplot").empty())
    throw EnvironmentError("gnuplot: not found on PATH; the report's figures need it (Debian package gnuplot-nox, "
                           "which ./run.sh installs)");
  ProgramCall call{{"gnuplot", "--version"}};
  call.timeout_seconds = kGnuplotVersionSeconds;
  const ProgramResult r = runProgram(call);
  if (r.timed_out)
    throw EnvironmentError("gnuplot: 'gnuplot --version' did not answer within " + formatNumber(kGnuplotVersionSeconds) +
                           " s; gnuplot was ended");
  std::string version = r.out;
  while (!version.empty() && (version.back() == '\n' || version.back() == '\r')) version.pop_back();
  if (r.exit_status != 0 || version.empty())
    throw EnvironmentError("gnuplot: 'gnuplot --version' failed: " + r.err);
  findReportsDir();  // the figures' scripts too, before the work (a CRANKCHECK_REPORTS_DIR that names no folder)
  return version;
}

}  // namespace crankcheck::validation
