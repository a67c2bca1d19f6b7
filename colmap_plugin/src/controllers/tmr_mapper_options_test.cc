// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>

#include "tmr/colmap/tmr_mapper.h"

namespace tmr {
namespace {

// Every row's default is allowed, and the names are unique.
TEST(TmrMapperOptions, DefaultsPassTheirRowsAndNamesAreUnique) {
  TmrMapperOptions options;
  options.database_path = "db";
  options.output_path = "out";
  std::string error;
  EXPECT_TRUE(options.Check(&error)) << error;
  OptionTable table;
  options.AddTo(&table);
  std::set<std::string> names;
  for (const OptionRow& row : table.rows())
    EXPECT_TRUE(names.insert(row.name).second) << row.name;
  EXPECT_GT(table.rows().size(), 50u);

  options.tree.kernels.alpha = 0.5;
  EXPECT_FALSE(options.Check(&error));
  EXPECT_EQ(error, "Tmr.alpha must be >= 1");
  options.tree.kernels.alpha = 1.5;
  options.mapper.init_max_forward_motion = std::nan("");
  EXPECT_FALSE(options.Check(&error));
  EXPECT_EQ(error, "Mapper.init_max_forward_motion must be in [0, 1]");
}

}  // namespace
}  // namespace tmr
