// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "tmr/util/option_table.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>
#include <string>

#include "tmr/partition/tmr_tree.h"

namespace tmr {
namespace {

struct ToyOptions {
  int count = 3;
  double share = 0.5;
  bool flag = true;
  uint64_t seed = 7;
  std::string mode = "auto";

  void AddTo(OptionTable* t) {
    t->Add("Toy.count", &count, "a count").AtLeast(1).ChangesTasks();
    t->Add("Toy.share", &share, "a share").Above(0).AtMost(1);
    t->Add("Toy.flag", &flag, "a flag");
    t->Add("Toy.seed", &seed, "a seed").ChangesTasks();
    t->Add("Toy.mode", &mode, "a mode").RunSetting();
  }
};

TEST(OptionTable, ChecksBoundsAndNamesTheOptionThatFails) {
  ToyOptions options;
  std::string error;
  EXPECT_TRUE(CheckOptionRows(options, &error));
  options.count = 0;
  EXPECT_FALSE(CheckOptionRows(options, &error));
  EXPECT_EQ(error, "Toy.count must be >= 1");
  options.count = 1;
  for (const double bad :
       {0.0, 1.5, std::nan(""), std::numeric_limits<double>::infinity()}) {
    options.share = bad;
    EXPECT_FALSE(CheckOptionRows(options, &error)) << bad;
    EXPECT_EQ(error, "Toy.share must be in (0, 1]");
  }
  options.share = 1.0;
  EXPECT_TRUE(CheckOptionRows(options, &error));
}

TEST(OptionTable, ValuesAreExactAndListTheRowsAsked) {
  ToyOptions options;
  options.share = 0.1 + 0.2;  // 0.30000000000000004: needs 17 digits
  OptionTable table;
  options.AddTo(&table);
  EXPECT_EQ(table.Values(),
            "Toy.count=3\nToy.share=0.30000000000000004\nToy.flag=1\n"
            "Toy.seed=7\nToy.mode=auto\n");
  EXPECT_EQ(table.Values(OptionTable::Rows::kTasks),
            "Toy.count=3\nToy.seed=7\n");
  EXPECT_EQ(table.Values(OptionTable::Rows::kResults),
            "Toy.count=3\nToy.share=0.30000000000000004\nToy.flag=1\n"
            "Toy.seed=7\n");
  EXPECT_EQ(std::stod(ExactDoubleText(options.share)), options.share);
  EXPECT_EQ(ExactDoubleText(0.3), "0.3");
  ASSERT_NE(table.Find("Toy.mode"), nullptr);
  EXPECT_EQ(table.Find("Toy.none"), nullptr);
}

// The partition's table: unique names, defaults allowed, and each struct's
// Check reports the row by its command-line name.
TEST(OptionTable, TreeOptionsHaveUniqueNamesAndAllowedDefaults) {
  TmrTreeOptions options;
  OptionTable table;
  options.AddTo(&table);
  std::set<std::string> names;
  for (const OptionRow& row : table.rows()) {
    EXPECT_TRUE(names.insert(row.name).second) << row.name;
    EXPECT_EQ(row.name.rfind("Tmr.", 0), 0u) << row.name;
    EXPECT_EQ(row.Problem(), "") << row.name;
    EXPECT_FALSE(row.help.empty()) << row.name;
  }
  EXPECT_EQ(names.size(), 27u);
  std::string error;
  options.image_clustering.num_layers = 0;
  EXPECT_FALSE(options.Check(&error));
  EXPECT_EQ(error, "Tmr.msp_layers must be >= 1");
  options.image_clustering.num_layers = 20;
  options.kernels.kernel_size_floor = 100;
  EXPECT_FALSE(options.Check(&error));
  EXPECT_EQ(error,
            "Tmr.min_kernel_size and Tmr.kernel_size_floor must be at most "
            "Tmr.max_kernel_size");
}

}  // namespace
}  // namespace tmr
