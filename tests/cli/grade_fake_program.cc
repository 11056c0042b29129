// Programs that misbehave, for tests/cli/grade_test.cc: `grade_fake_program MODE` reads its request(s) from stdin
// and then does what MODE says.
#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

int main(int argc, char** argv) {
  const std::string mode = argc > 1 ? argv[1] : "";
  std::string line, first;
  std::vector<std::string> lines;  // every request (--batch: several)
  size_t requests = 0;  // one per line (--batch: several)
  if (mode != "no-read")
    while (std::getline(std::cin, line)) {
      if (first.empty()) first = line;
      requests += !line.empty();
      if (!line.empty()) lines.push_back(line);
    }
  if (mode == "silent" || mode == "no-read") return 0;
  // The number of angles of the request, to answer with the right number of results.
  const size_t at = first.find("\"phi_deg\":[");
  size_t n = 1;
  for (size_t i = at; at != std::string::npos && i < first.size() && first[i] != ']'; ++i) n += first[i] == ',';
  auto repeat = [n](const std::string& result) {
    std::string out = "{\"results\": [";
    for (size_t i = 0; i < n; ++i) out += (i ? "," : "") + result;
    return out + "]}";
  };
  if (mode == "batch-bad-third") {  // --batch: a blank line, then every response valid but the third one's
    std::puts("");
    for (size_t i = 0; i < lines.size(); ++i) {
      const size_t phi = lines[i].find("\"phi_deg\":[");
      size_t angles = 1;
      for (size_t c = phi; phi != std::string::npos && c < lines[i].size() && lines[i][c] != ']'; ++c) angles += lines[i][c] == ',';
      std::string out = "{\"results\": [";
      for (size_t a = 0; a < angles; ++a) out += (a ? "," : "") + std::string(i == 2 ? "{\"U\": \"12 J\"}" : "{}");
      std::puts((out + "]}").c_str());
    }
    return 0;
  }
  if (mode == "garbage") {
    std::puts("hello, this is not JSON {");
    return 0;
  }
  if (mode == "no-results") {
    std::puts("{\"answers\": []}");
    return 0;
  }
  if (mode == "wrong-count") {
    std::puts("{\"results\": [{}]}");
    return 0;
  }
  if (mode == "nan") {
    std::puts(repeat("{\"U\": NaN}").c_str());
    return 0;
  }
  if (mode == "string") {
    std::puts(repeat("{\"U\": \"12 J\"}").c_str());
    return 0;
  }
  if (mode == "crash") std::abort();
  if (mode == "exit7") {
    std::fputs("something went wrong in the model\n", stderr);
    return 7;
  }
  if (mode == "traceback") {  // as Python dies: what failed is the last line, after the call stack
    std::fputs("Traceback (most recent call last):\n  File \"sim.py\", line 12, in <module>\n    main()\n"
               "  File \"sim.py\", line 9, in main\n    x = 1 / 0\nZeroDivisionError: division by zero\n", stderr);
    return 1;
  }
  // Answers, leaves a child in a session of its own (holding stdout; or, as a daemon, with stdout and stderr on
  // /dev/null), writes the child's pid to argv[2] and exits 0. The child would sleep 60 s.
  if (mode == "setsid-child" || mode == "daemon-child") {
    std::puts(repeat("{}").c_str());
    std::fflush(stdout);
    const pid_t child = ::fork();
    if (child == 0) {
      ::setsid();
      if (mode == "daemon-child") {
        const int null = ::open("/dev/null", O_WRONLY);
        ::dup2(null, STDOUT_FILENO);
        ::dup2(null, STDERR_FILENO);
      }
      ::sleep(60);
      ::_exit(0);
    }
    if (argc > 2) std::ofstream(argv[2]) << child << "\n";
    return 0;
  }
  if (mode == "pipeline-flood") {  // a child in its own process group writes 70 MB (past the 64 MiB limit), as `... | cat`
    if (::fork() == 0) {
      const std::string block(1 << 20, 'a');
      for (int i = 0; i < 70; ++i) std::fwrite(block.data(), 1, block.size(), stdout);
      std::fflush(stdout);
      ::_exit(0);
    }
    ::wait(nullptr);
    return 0;
  }
  if (mode == "hang") {
    for (;;) ::pause();
  }
  if (mode == "huge") {
    const std::string block(1 << 20, ' ');
    for (int i = 0; i < 100; ++i) std::fwrite(block.data(), 1, block.size(), stdout);  // 100 MiB of blanks
    return 0;
  }
  if (mode == "control-bytes") {
    // A terminal's escape sequences, a NUL and a tab in a line that is not JSON: quoted in the message, escaped.
    const char text[] = "\x1b[2J\x1b[31mred\x1b[0m\0\tafter NUL\n";
    std::fwrite(text, 1, sizeof text - 1, stdout);
    return 0;
  }
  if (mode == "control-bytes-stderr") {
    const char text[] = "\x1b]0;title\x07\0hidden\n";
    std::fwrite(text, 1, sizeof text - 1, stderr);
    return 7;
  }
  if (mode == "answer-then-hang") {
    // A complete, valid answer to every request (nothing provided), and then no exit.
    for (size_t i = 0; i < requests; ++i) std::puts(repeat("null").c_str());
    std::fflush(stdout);
    for (;;) ::pause();
  }
  if (mode == "tiny-at-rest") {
    // At rest (the scene's speed 0): 1e-18 for each quantity of argv[2] (comma-separated), every cylinder; at speed
    // nothing. A value of 1e-18 where the truth is 0 is rounding, and must pass.
    const std::string wanted = "," + std::string(argc > 2 ? argv[2] : "") + ",";
    auto field = [&first](const std::string& key) {
      const size_t k = first.find("\"" + key + "\":");
      return k == std::string::npos ? -1.0 : std::strtod(first.c_str() + k + key.size() + 3, nullptr);
    };
    const int cylinders = static_cast<int>(field("cylinders"));
    if (field("speed") != 0.0 || cylinders < 1) {
      std::puts(repeat("null").c_str());
      return 0;
    }
    auto has = [&wanted](const char* q) {
      std::string item = ",";
      item += q;
      return wanted.find(item += ',') != std::string::npos;
    };
    std::string result = "{", cylinder = "{";
    auto add = [](std::string& to, const char* key, int n) {
      to += std::string(to.size() > 1 ? "," : "") + "\"" + key + "\":";
      if (n == 1) to += "1e-18";
      else to += n == 2 ? "[1e-18,1e-18]" : "[1e-18,1e-18,1e-18]";
    };
    for (const char* q : {"U", "Q", "drive_torque"}) if (has(q)) add(result, q, 1);
    for (const char* q : {"bearing_force", "shaking_force"}) if (has(q)) add(result, q, 2);
    if (has("shaking_moment")) add(result, "shaking_moment", 3);
    for (const char* q : {"v_p", "a_p", "wall_force", "rod_omega", "rod_alpha"}) if (has(q)) add(cylinder, q, 1);
    for (const char* q : {"crank_pin_force", "wrist_pin_force"}) if (has(q)) add(cylinder, q, 2);
    cylinder += "}";
    result += std::string(result.size() > 1 ? "," : "") + "\"cylinders\":[";
    for (int j = 0; j < cylinders; ++j) result += (j ? "," : "") + cylinder;
    std::puts(repeat(result + "]}").c_str());
    return 0;
  }
  if (mode == "duplicate-key") {  // one result gives U twice: which one counts is not defined
    std::string out = "{\"results\": [";
    for (size_t i = 0; i < n; ++i) out += std::string(i ? "," : "") + (i == 1 ? "{\"U\": 12345.0, \"U\": null}" : "null");
    std::puts((out + "]}").c_str());
    return 0;
  }
  if (mode == "misspelled-key") {  // "Uu" for U: not provided without a word, once
    std::string out = "{\"results\": [";
    for (size_t i = 0; i < n; ++i) out += std::string(i ? "," : "") + (i == 1 ? "{\"Uu\": 1.0}" : "null");
    std::puts((out + "]}").c_str());
    return 0;
  }
  if (mode == "extra-top-key") {  // a key beside "results" (with an ESC in its name): not the protocol
    std::string out = "{\"results\": [";
    for (size_t i = 0; i < n; ++i) out += std::string(i ? "," : "") + "null";
    std::puts((out + "], \"extra\\u001b\": 1}").c_str());
    return 0;
  }
  if (mode == "nothing-provided") {
    // As many results as angles, each empty or null: valid protocol, nothing to grade.
    std::string out = "{\"results\": [";
    for (size_t i = 0; i < n; ++i) out += std::string(i ? "," : "") + (i % 2 ? "null" : "{\"U\": null, \"cylinders\": [null]}");
    std::puts((out + "]}").c_str());
    return 0;
  }
  std::fprintf(stderr, "grade_fake_program: unknown mode %s\n", mode.c_str());
  return 2;
}
