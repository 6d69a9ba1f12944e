// One digital input line (the arm's e-stop): read without blocking. The
// libgpiod backend and the HIL bench come with the hardware HAL; tests and the
// simulator use a settable line.
#pragma once

#include "algo/core/result.hpp"

namespace petra::hal {

class DigitalInput {
 public:
  virtual ~DigitalInput() = default;
  // true when the line is asserted (active), false otherwise; an error when
  // the line cannot be read (treated as asserted by safety users).
  virtual Result<bool> read() = 0;
};

// A line set by software (tests, simulation).
class SettableInput final : public DigitalInput {
 public:
  void set(bool asserted) { asserted_ = asserted; }
  Result<bool> read() override { return asserted_; }

 private:
  bool asserted_ = false;
};

}  // namespace petra::hal
