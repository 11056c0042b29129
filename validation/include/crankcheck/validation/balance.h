#pragma once
/// @file
/// Balance: the shaking force and moment harmonic by harmonic, from every exact engine. The analytic engine gives each
/// harmonic in closed form (analytic/shaking.h: calcShakingHarmonics) and decides exactly which vanish by symmetry
/// (findHarmonicSymmetry); each other exact engine's harmonics (Simbody, MuJoCo: engines.h, listReferenceEngines)
/// come from a DFT of its own shaking force and moment over one revolution (its evaluate at `samples` equally spaced
/// crank angles).

#include <string>
#include <utility>
#include <vector>

#include "crankcheck/analytic/shaking.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/scene/mechanism.h"

namespace crankcheck::validation {

struct BalanceRow {
  int n = 0;
  analytic::ShakingHarmonic analytic;   ///< closed form
  /// (engine name, DFT of that engine's F_s and M_s) for every reference engine, in the registry's order
  std::vector<std::pair<std::string, analytic::ShakingHarmonic>> engines;
  analytic::HarmonicSymmetry symmetry;  ///< what vanishes exactly by the layout's symmetry
  /// The harmonic of engine `name`. @throws std::out_of_range if that engine was not evaluated.
  const analytic::ShakingHarmonic& of(const std::string& name) const;
};

/// What a DFT of an engine's shaking resolves [N], [N m]: the gate's rule for balance, 2 x kAgreementMultiple x eps x
/// the force (moment) scale x the acceleration conditioning (scales.h; the DFT sums N samples each within the rule,
/// weighted 2/N: its rounding stays below twice a sample's). An engine's amplitude below it is that engine's rounding;
/// an engine's harmonic that differs from the closed form's by more does not hold its accuracy on the scene.
struct BalanceResolution {
  double force = 0.0;   ///< [N]
  double moment = 0.0;  ///< [N m]
};
BalanceResolution calcBalanceResolution(const Mechanism& m);

/// Where harmonic `dft` (an engine's) differs from `closed` (the closed form's) beyond `resolution`, part by part
/// (F's X and Y, M's X, Y, Z, each cosine and sine): "harmonic N's F_X cosine differs from the closed form by D N,
/// beyond the resolution R N"; "" where every part agrees. A part that is not finite always differs.
std::string findBalanceDisagreement(const analytic::ShakingHarmonic& closed, const analytic::ShakingHarmonic& dft,
                                    int n, const BalanceResolution& resolution);

/// Harmonics 1..order of every exact engine. `samples` = 0 chooses max(64, 4 order) angles per revolution: the DFT then
/// folds harmonic samples - n onto n, whose size is below lambda^(samples - n) times the primary (nothing at engine
/// crank ratios).
/// @throws std::invalid_argument if order < 1 or samples is not 0 and below 2 order + 1, or an engine cannot build m
///         (the message names the engine); std::runtime_error if an engine fails.
/// `sat_out`: null, a reference engine that cannot build m is an error (std::invalid_argument naming it), and every
/// engine's DFT is returned as computed (the gate compares them itself); given, an engine that cannot build m, or
/// whose DFT differs from the closed form beyond calcBalanceResolution (findBalanceDisagreement), sits out and is
/// added there with its reason, and the others answer. None left: std::invalid_argument when every engine refused
/// the scene, std::runtime_error when one computed it and disagreed (the closed form is not confirmed).
std::vector<BalanceRow> calcBalance(const Mechanism& m, int order, int samples = 0, std::vector<SatOut>* sat_out = nullptr);

/// The closed-form harmonic h with the parts that vanish exactly by the layout's symmetry s set to 0 (they are
/// rounding otherwise); h itself where s is not decided.
analytic::ShakingHarmonic withExactZeros(analytic::ShakingHarmonic h, const analytic::HarmonicSymmetry& s);

/// Balance shafts that cancel harmonic n of the shaking force exactly as the closed form gives it (including the
/// scene's own shafts): F_n(phi) = F+ e^{i n phi} + F- e^{-i n phi} (X + iY), each turning part cancelled by one shaft
/// turning with it, ratio +n against F+ and -n against F-, its mass at the crank radius r with m r (n omega)^2 = |F|
/// and its phase opposite (a part below 64 eps of the force scale gets no shaft). The shafts sit below the crank at
/// (+-r, -2 r) in the mean plane of the cylinders (a starting point: their position moves only the moments). The
/// shaking and a shaft's force both scale with omega^2: a scene at rest is designed at 1 rad/s, the same shafts.
/// @throws std::invalid_argument if n < 1 or a shaft of the scene has a ratio that is not a whole number.
std::vector<BalanceShaftParams> designBalanceShafts(const Mechanism& m, int n);


}  // namespace crankcheck::validation
