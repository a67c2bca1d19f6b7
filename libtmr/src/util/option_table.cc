// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "tmr/util/option_table.h"

#include <cmath>
#include <sstream>
#include <type_traits>

namespace tmr {
namespace {

std::string Number(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

}  // namespace

std::string ExactDoubleText(double value) {
  std::string text;
  for (int digits = 15; digits <= 17; ++digits) {
    std::ostringstream out;
    out.precision(digits);
    out << value;
    text = out.str();
    if (std::stod(text) == value) break;
  }
  return text;
}

OptionRow::OptionRow(std::string name, Value value, std::string help)
    : name(std::move(name)), value(value), help(std::move(help)) {}

OptionRow& OptionRow::AtLeast(double bound) {
  min = bound;
  min_exclusive = false;
  return *this;
}

OptionRow& OptionRow::Above(double bound) {
  min = bound;
  min_exclusive = true;
  return *this;
}

OptionRow& OptionRow::AtMost(double bound) {
  max = bound;
  max_exclusive = false;
  return *this;
}

OptionRow& OptionRow::Below(double bound) {
  max = bound;
  max_exclusive = true;
  return *this;
}

OptionRow& OptionRow::ChangesTasks() {
  changes_tasks = true;
  return *this;
}

OptionRow& OptionRow::RunSetting() {
  run_setting = true;
  return *this;
}

std::string OptionRow::Problem() const {
  double x = 0;
  bool is_double = false;
  if (const auto* p = std::get_if<int*>(&value)) {
    x = **p;
  } else if (const auto* q = std::get_if<uint64_t*>(&value)) {
    x = static_cast<double>(**q);
  } else if (const auto* d = std::get_if<double*>(&value)) {
    x = **d;
    is_double = true;
  } else {
    return "";  // bools and text take any value
  }
  const bool low_ok = min_exclusive ? x > min : x >= min;  // false for NaN
  const bool high_ok = max_exclusive ? x < max : x <= max;
  if (low_ok && high_ok && (!is_double || std::isfinite(x))) return "";
  const bool has_min = std::isfinite(min), has_max = std::isfinite(max);
  std::string allowed;
  if (has_min && has_max) {
    allowed = "in " + std::string(min_exclusive ? "(" : "[") + Number(min) +
              ", " + Number(max) + (max_exclusive ? ")" : "]");
  } else if (has_min) {
    allowed = (min_exclusive ? "> " : ">= ") + Number(min);
  } else if (has_max) {
    allowed = (max_exclusive ? "< " : "<= ") + Number(max);
  } else {
    allowed = "finite";
  }
  return name + " must be " + allowed;
}

std::string OptionRow::ValueText() const {
  return std::visit(
      [](const auto* field) -> std::string {
        using T = std::decay_t<decltype(*field)>;
        if constexpr (std::is_same_v<T, std::string>) {
          return *field;
        } else if constexpr (std::is_same_v<T, double>) {
          return ExactDoubleText(*field);
        } else if constexpr (std::is_same_v<T, bool>) {
          return *field ? "1" : "0";
        } else {
          return std::to_string(*field);
        }
      },
      value);
}

bool OptionTable::Check(std::string* error) const {
  for (const OptionRow& row : rows_) {
    const std::string problem = row.Problem();
    if (problem.empty()) continue;
    if (error) *error = problem;
    return false;
  }
  return true;
}

std::string OptionTable::Values(Rows rows) const {
  std::string text;
  for (const OptionRow& row : rows_) {
    if ((rows == Rows::kTasks && !row.changes_tasks) ||
        (rows == Rows::kResults && row.run_setting))
      continue;
    text += row.name + "=" + row.ValueText() + "\n";
  }
  return text;
}

OptionRow* OptionTable::Find(const std::string& name) {
  for (OptionRow& row : rows_) {
    if (row.name == name) return &row;
  }
  return nullptr;
}

}  // namespace tmr
