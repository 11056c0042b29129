// scene_check: the scene parser as a filter, for tests/scene/schema_test.py. Reads scene texts from stdin, separated
// by NUL bytes (TOML text has none), parses each with crankcheck::parseScene and prints one line per scene:
// "ok", or "refused<TAB>MESSAGE" (the message crankcheck would print after "crankcheck: "). Exit status 0 when every
// scene got a verdict, 1 if the parser failed in any other way (a bug: it throws only SceneError on bad input).

#include <iostream>
#include <iterator>
#include <string>

#include "crankcheck/scene/scene_file.h"

int main() {
  const std::string input((std::istreambuf_iterator<char>(std::cin)), std::istreambuf_iterator<char>());
  int status = 0;
  size_t begin = 0;
  while (begin <= input.size()) {
    size_t end = input.find('\0', begin);
    if (end == std::string::npos) end = input.size();
    const std::string text = input.substr(begin, end - begin);
    try {
      crankcheck::parseScene(text, "scene.toml");
      std::cout << "ok\n";
    } catch (const crankcheck::SceneError& e) {
      std::cout << "refused\t" << e.what() << "\n";
    } catch (const std::exception& e) {
      std::cout << "error\t" << e.what() << "\n";
      status = 1;
    }
    begin = end + 1;
  }
  return status;
}
