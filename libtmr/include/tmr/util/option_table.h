// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// The one definition of every option: an options struct lists its fields in
// an OptionTable (name, help, allowed values, whether it changes a
// reconstruction task), and the command line, project.ini, tree.json,
// tmr_mapper's resume fingerprint and the struct's Check() all read that
// table. A default is the struct's member initializer.
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <variant>
#include <vector>

namespace tmr {

// One option: a field of one options object.
struct OptionRow {
  using Value = std::variant<bool*, int*, double*, uint64_t*, std::string*>;

  OptionRow(std::string name, Value value, std::string help);

  // Allowed values (numbers; a double must also be finite).
  OptionRow& AtLeast(double bound);
  OptionRow& Above(double bound);
  OptionRow& AtMost(double bound);
  OptionRow& Below(double bound);
  // A kernel or leaf task made with another value is not reused on resume.
  OptionRow& ChangesTasks();
  // How a run goes (threads, memory, resuming), not what it makes: left
  // out of the record of a finished step, so that another run with another
  // value reuses it.
  OptionRow& RunSetting();

  // "" when the value is allowed, else "NAME must be >= 1" and the like.
  std::string Problem() const;
  // The value as text, doubles exact (the shortest of 15 to 17 digits
  // that reads back as the same number), bools 0 or 1.
  std::string ValueText() const;

  std::string name;  // --NAME on the command line, NAME= in project.ini
  Value value;
  std::string help;
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_exclusive = false;
  bool max_exclusive = false;
  bool changes_tasks = false;
  bool run_setting = false;
};

class OptionTable {
 public:
  template <typename T>
  OptionRow& Add(std::string name, T* value, std::string help) {
    rows_.emplace_back(std::move(name), value, std::move(help));
    return rows_.back();
  }

  // False with the first row's problem (OptionRow::Problem) in `error`.
  bool Check(std::string* error) const;
  // Which rows Values lists: all, those that change what a run makes (not
  // RunSetting), those that change tasks (ChangesTasks).
  enum class Rows { kAll, kResults, kTasks };
  // "NAME=VALUE\n" per row, in order.
  std::string Values(Rows rows = Rows::kAll) const;
  // The row called `name`, or nullptr.
  OptionRow* Find(const std::string& name);

  const std::vector<OptionRow>& rows() const { return rows_; }

 private:
  std::vector<OptionRow> rows_;
};

// The shortest of 15 to 17 significant digits that reads back as `value`:
// a later stage reads project.ini and must see the same options.
std::string ExactDoubleText(double value);

// Checks the rows of an options struct with a `void AddTo(OptionTable*)`
// (on a copy: the table points into the object it lists).
template <typename Options>
bool CheckOptionRows(const Options& options, std::string* error) {
  Options copy = options;
  OptionTable table;
  copy.AddTo(&table);
  return table.Check(error);
}

}  // namespace tmr
