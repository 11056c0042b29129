#pragma once
#include <stdexcept>

namespace crankcheck::app {

/// A user error (bad scene, bad flag value): main prints the message alone and exits with status 2.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace crankcheck::app
