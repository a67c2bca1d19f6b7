// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// The partition as text, as tmr_partition prints it.
#pragma once

#include <ostream>

#include "tmr/partition/tmr_tree.h"

namespace tmr {

// Prints kernels, image clusters and leaf clusters with their sizes, the
// unclustered images and the time per stage.
void PrintTreeSummary(const TmrTree& tree, std::ostream& out);

}  // namespace tmr
