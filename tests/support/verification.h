#pragma once
/// The verification manual's records (docs/verification.md, scripts/verification.py): a test
/// that compares the engine with a hand value calls recordVerification with the case, its
/// source, the hand value, the measured value and the tolerance of its own assertion. When
/// the environment variable ROCKMASS_VERIFICATION_DIR is set (scripts/test.sh sets it), one
/// JSON line is appended to `$ROCKMASS_VERIFICATION_DIR/<program>.<test>.jsonl`; otherwise
/// nothing happens. The record never asserts: the test's own EXPECT_NEAR stays the check.
///
/// Numbers are written as text with limited precision, so that the manual is byte-identical
/// run to run: expected and measured values with 4 significant digits, errors with 2. A
/// value or an error smaller than 1/100 of the absolute tolerance (round-off, a block at
/// rest) is written as an upper bound, the power of ten above that 1/100 ("< 1e-09"),
/// instead of its digits: round-off has no reproducible digits.
#include <gtest/gtest.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#ifndef ROCKMASS_TEST_PROGRAM
#define ROCKMASS_TEST_PROGRAM "tests"
#endif

namespace rockmass::test {

/// How a measured value is judged against the hand value.
enum class Compare {
  Near,     ///< |measured - expected| <= tolerance (absolute or relative to |expected|)
  AtLeast,  ///< measured >= expected (a bound; the tolerance is not used)
  AtMost,   ///< measured <= expected (a bound; the tolerance is not used)
};

/// One row of the verification manual.
struct Verification {
  std::string group;   ///< the manual's table, e.g. "Wedges" (scripts/verification.py lists them)
  std::string name;    ///< the case, unique in the manual
  std::string source;  ///< book or paper and chapter, and the formula
  double expected = 0.0;  ///< the hand value (or the bound, for AtLeast / AtMost)
  double measured = 0.0;  ///< what the engine gave
  double tolerance = 0.0;
  bool relative = false;  ///< tolerance relative to |expected| (else absolute, in `unit`)
  std::string unit;       ///< of expected and measured ("m", "m/s2", "-", "deg", ...)
  Compare compare = Compare::Near;
};

namespace verification_detail {

/// `x` with `digits` significant digits: fixed notation for 1e-3 <= |x| < 1e5, else
/// scientific with a two-digit exponent; never "-0".
inline std::string significant(double x, int digits) {
  if (!std::isfinite(x)) return std::isnan(x) ? "nan" : (x > 0 ? "inf" : "-inf");
  if (x == 0.0) return "0";
  char buffer[64];
  const double magnitude = std::abs(x);
  const bool fixed = magnitude >= 1e-3 && magnitude < 1e5;
  std::to_chars_result r;
  if (fixed) {
    const int exponent = static_cast<int>(std::floor(std::log10(magnitude)));
    const int decimals = std::max(0, digits - 1 - exponent);
    r = std::to_chars(buffer, buffer + sizeof buffer, x, std::chars_format::fixed, decimals);
  } else {
    r = std::to_chars(buffer, buffer + sizeof buffer, x, std::chars_format::scientific, digits - 1);
  }
  std::string text(buffer, r.ptr);
  if (text.find_first_not_of("-0.") == std::string::npos) return "0";
  return text;
}

/// `x` with `digits` significant digits and no trailing zeros ("1", "0.5", "1e-06").
inline std::string trimmed(double x, int digits) {
  std::string text = significant(x, digits);
  const std::size_t e = text.find('e');
  std::string mantissa = text.substr(0, e), exponent = e == std::string::npos ? "" : text.substr(e);
  if (mantissa.find('.') != std::string::npos) {
    mantissa.erase(mantissa.find_last_not_of('0') + 1);
    if (mantissa.back() == '.') mantissa.pop_back();
  }
  return mantissa + exponent;
}

/// The smallest power of ten at or above `x` (> 0), as text ("1e-09").
inline std::string powerOfTenAbove(double x) {
  const int exponent = static_cast<int>(std::ceil(std::log10(x) - 1e-9));
  return trimmed(std::pow(10.0, exponent), 1);
}

/// `value` with `digits` significant digits, or "< 10^k" when |value| < floor (> 0).
inline std::string bounded(double value, int digits, double floor) {
  if (floor > 0.0 && std::abs(value) < floor) return "< " + powerOfTenAbove(floor);
  return significant(value, digits);
}

inline std::string escaped(const std::string& s) {
  std::string out;
  for (const char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      out += ' ';
    } else {
      out += c;
    }
  }
  return out;
}

/// "Suite.Name" of the running test, with '/' of parameterised names made '_'.
inline std::string currentTestName() {
  const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
  if (!info) return "unknown";
  return std::string(info->test_suite_name()) + "." + info->name();
}

}  // namespace verification_detail

/// Appends `v` to the manual's records (no-op unless ROCKMASS_VERIFICATION_DIR is set).
inline void recordVerification(const Verification& v) {
  namespace d = verification_detail;
  constexpr double kFloor = 1e-2;  // of the tolerance: below it, written as a bound
  const char* dir = std::getenv("ROCKMASS_VERIFICATION_DIR");
  if (!dir || !*dir) return;
  const double absolute_tolerance = v.relative ? v.tolerance * std::abs(v.expected) : v.tolerance;
  std::string tolerance, error;
  bool within = false;
  const std::string unit = v.unit == "-" ? "" : " " + v.unit;
  switch (v.compare) {
    case Compare::Near: {
      within = std::abs(v.measured - v.expected) <= absolute_tolerance;
      if (v.relative) {
        tolerance = d::trimmed(100.0 * v.tolerance, 2) + " %";
        error = d::bounded(100.0 * (v.measured - v.expected) / std::abs(v.expected), 2,
                           kFloor * 100.0 * v.tolerance) +
                " %";
      } else {
        tolerance = d::trimmed(v.tolerance, 2) + unit;
        error = d::bounded(v.measured - v.expected, 2, kFloor * v.tolerance) + unit;
      }
      break;
    }
    case Compare::AtLeast:
      within = v.measured >= v.expected;
      tolerance = "bound";
      error = "";
      break;
    case Compare::AtMost:
      within = v.measured <= v.expected;
      tolerance = "bound";
      error = "";
      break;
  }
  const double floor = v.compare == Compare::Near ? kFloor * absolute_tolerance : 0.0;
  std::string expected = d::significant(v.expected, 4);
  if (v.compare == Compare::AtLeast) expected = ">= " + d::trimmed(v.expected, 4);
  if (v.compare == Compare::AtMost) expected = "<= " + d::trimmed(v.expected, 4);
  // A bound on a round-off quantity (at rest, no NaN): below 1/100 of the bound, a bound.
  const double measured_floor =
      v.compare == Compare::AtMost ? kFloor * std::abs(v.expected) : floor;
  const std::string measured = d::bounded(v.measured, 4, measured_floor);

  const std::string test = d::currentTestName();
  std::string file = std::string(ROCKMASS_TEST_PROGRAM) + "." + test + ".jsonl";
  std::replace(file.begin(), file.end(), '/', '_');
  std::filesystem::create_directories(dir);
  std::ofstream out(std::filesystem::path(dir) / file, std::ios::app | std::ios::binary);
  out << "{\"group\": \"" << d::escaped(v.group) << "\", \"case\": \"" << d::escaped(v.name)
      << "\", \"source\": \"" << d::escaped(v.source) << "\", \"expected\": \"" << expected
      << "\", \"measured\": \"" << measured << "\", \"unit\": \"" << d::escaped(v.unit)
      << "\", \"tolerance\": \"" << tolerance << "\", \"error\": \"" << error
      << "\", \"within\": " << (within ? "true" : "false") << ", \"test\": \""
      << ROCKMASS_TEST_PROGRAM << " " << d::escaped(test) << "\"}\n";
}

/// Records a dimensionless factor (a safety factor, K_s, SRF) checked within a relative
/// `tolerance` of its hand value.
inline void recordFactor(const std::string& group, const std::string& name,
                         const std::string& source, double expected, double measured,
                         double tolerance) {
  recordVerification({.group = group,
                      .name = name,
                      .source = source,
                      .expected = expected,
                      .measured = measured,
                      .tolerance = tolerance,
                      .relative = true,
                      .unit = "-"});
}

}  // namespace rockmass::test
