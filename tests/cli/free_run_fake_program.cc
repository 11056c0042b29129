// Time-stepped runs that misbehave or are simply wrong, for tests/cli/free_run_grade_test.cc:
// `free_run_fake_program MODE` reads one protocol-2 request from stdin and answers a run that does what MODE says.
// The valid run is the crank turning at exactly omega0 (phi = omega0 t): the protocol kept, the physics wrong (no
// speed fluctuation), so it must be graded, not refused.
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>

int main(int argc, char** argv) {
  const std::string mode = argc > 1 ? argv[1] : "";
  std::string line;
  if (!std::getline(std::cin, line)) return 4;
  if (mode == "hang")
    for (;;) ::pause();
  const nlohmann::json request = nlohmann::json::parse(line);
  const double t_end = request.at("t_end"), interval = request.at("output_interval"), omega0 = request.at("omega0");
  const long n = std::lround(t_end / interval);
  if (mode == "slow-by-steps" && request.at("dt").is_number()) {  // 0.3 s per run at 1/720 of a turn, more with the steps
    const double default_dt = 2.0 * M_PI / omega0 / 720.0;
    std::this_thread::sleep_for(std::chrono::duration<double>(0.3 * default_dt / request.at("dt").get<double>()));
  }
  nlohmann::json samples = nlohmann::json::array();
  for (long i = 0; i <= n; ++i) {
    const double t = i == n ? t_end : i * interval;
    nlohmann::json s = {{"t", t}, {"phi", omega0 * t}, {"omega", omega0}};
    if (mode == "time-back" && i == n / 2) s["t"] = t - 2.0 * interval;
    if (mode == "phi-back" && i == n / 2) s["phi"] = omega0 * (t - 2.0 * interval);
    if (mode == "held-torque") s["drive_torque"] = 0.0;  // wrong wherever gravity or inertia load the crank
    if (mode == "omega-t-far") s["omega_t"] = t + 1e6;    // every speed 1e6 s past its sample, in order
    if (mode == "values-t-far") s["values_t"] = t + 1e6;  // every value's instant as far out
    if (mode == "backwards") s["omega"] = -omega0;        // the right angles with the speed's sign lost
    if (mode == "short" && i > n / 2) break;
    if (mode == "few" && i >= 5) break;
    samples.push_back(s);
  }
  if (mode == "past-end") samples.push_back({{"t", 1e9}, {"phi", 1e9}, {"omega", omega0}});  // one sample 1e9 s on
  if (mode == "phi-far") samples.push_back({{"t", t_end + 0.5 * interval}, {"phi", 1e300}, {"omega", omega0}});
  std::string text = nlohmann::json{{"samples", samples}}.dump();
  if (mode == "nan") {  // a run that fell apart: nlohmann writes NaN as null, the grader must refuse it as not finite
    const size_t at = text.find("\"omega\":", text.size() / 2);
    text.replace(at, text.find_first_of(",}", at) - at, "\"omega\":NaN");
  }
  if (mode == "overflow") {  // a number past a double's range, on line 2 of the answer
    const size_t at = text.find("\"omega\":", text.size() / 2);
    text.replace(at, text.find_first_of(",}", at) - at, "\n\"omega\":1e400");
  }
  std::puts(text.c_str());
  return 0;
}
