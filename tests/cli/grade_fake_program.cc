// Programs that misbehave, for tests/cli/grade_test.cc: `grade_fake_program MODE` reads its request(s) from stdin
// and then does what MODE says.
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <string>

int main(int argc, char** argv) {
  const std::string mode = argc > 1 ? argv[1] : "";
  std::string line, first;
  if (mode != "no-read")
    while (std::getline(std::cin, line))
      if (first.empty()) first = line;
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
  if (mode == "hang") {
    for (;;) ::pause();
  }
  if (mode == "huge") {
    const std::string block(1 << 20, ' ');
    for (int i = 0; i < 100; ++i) std::fwrite(block.data(), 1, block.size(), stdout);  // 100 MiB of blanks
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
