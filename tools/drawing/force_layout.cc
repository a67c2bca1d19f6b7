// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "drawing/force_layout.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

#include "tmr/scene/graph_summary.h"

namespace tmr {
namespace {

using Position = std::array<double, 2>;

// A quadtree over the vertex positions; every cell holds the number of its
// vertices and the sum of their positions.
class QuadTree {
 public:
  explicit QuadTree(const std::vector<Position>& p) : p_(p) {
    double min_x = p[0][0], max_x = p[0][0], min_y = p[0][1], max_y = p[0][1];
    for (const Position& q : p) {
      min_x = std::min(min_x, q[0]), max_x = std::max(max_x, q[0]);
      min_y = std::min(min_y, q[1]), max_y = std::max(max_y, q[1]);
    }
    cells_.push_back(
        {min_x, min_y, std::max({max_x - min_x, max_y - min_y, 1e-9})});
    for (int v = 0; v < static_cast<int>(p.size()); ++v) Insert(v);
  }

  // Adds the repulsion k^2 / d (k = 1) that every other vertex exerts on v.
  void AddRepulsion(int v, double theta, Position* force) const {
    const Position& q = p_[v];
    int stack[4 * kMaxDepth + 4];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Cell& c = cells_[stack[--top]];
      if (c.mass == 0) continue;
      const double dx = q[0] - c.sum_x / c.mass, dy = q[1] - c.sum_y / c.mass;
      const double d2 = dx * dx + dy * dy;
      if (c.child >= 0 && c.size * c.size >= theta * theta * d2) {
        for (int i = 0; i < 4; ++i) stack[top++] = c.child + i;
        continue;
      }
      // A leaf, or a cell far enough to act as one body. Coincident
      // vertices (and v itself) exert nothing.
      if (d2 < 1e-18) continue;
      (*force)[0] += dx * c.mass / d2;
      (*force)[1] += dy * c.mass / d2;
    }
  }

 private:
  // Below this depth coincident vertices share a leaf.
  static constexpr int kMaxDepth = 48;
  struct Cell {
    double x0, y0, size;
    int mass = 0;
    double sum_x = 0, sum_y = 0;
    int child = -1;   // first of the 4 children, or -1 for a leaf
    int vertex = -1;  // a leaf's first vertex
  };

  int Quadrant(const Cell& c, const Position& q) const {
    const double half = c.size / 2;
    return (q[0] >= c.x0 + half ? 1 : 0) + (q[1] >= c.y0 + half ? 2 : 0);
  }

  void Insert(int v) {
    int c = 0;
    for (int depth = 0;; ++depth) {
      cells_[c].mass += 1;
      cells_[c].sum_x += p_[v][0], cells_[c].sum_y += p_[v][1];
      if (cells_[c].child >= 0) {
        c = cells_[c].child + Quadrant(cells_[c], p_[v]);
        continue;
      }
      if (cells_[c].mass == 1) {
        cells_[c].vertex = v;
        return;
      }
      if (depth >= kMaxDepth) return;
      // Split the leaf; its vertex moves one level down.
      const Cell leaf = cells_[c];
      const double half = leaf.size / 2;
      cells_[c].child = static_cast<int>(cells_.size());
      for (int i = 0; i < 4; ++i) {
        cells_.push_back(
            {leaf.x0 + (i & 1 ? half : 0), leaf.y0 + (i & 2 ? half : 0), half});
      }
      Cell& moved = cells_[cells_[c].child + Quadrant(leaf, p_[leaf.vertex])];
      moved.mass = 1, moved.vertex = leaf.vertex;
      moved.sum_x = p_[leaf.vertex][0], moved.sum_y = p_[leaf.vertex][1];
      c = cells_[c].child + Quadrant(leaf, p_[v]);
    }
  }

  const std::vector<Position>& p_;
  std::vector<Cell> cells_;
};

// Fruchterman-Reingold on one connected graph, from a random start in a
// square of side sqrt(n); no bounds (the caller places the result).
std::vector<Position> LayoutConnected(int num_vertices,
                                      const std::vector<WeightedEdge>& edges,
                                      const ForceLayoutOptions& options,
                                      std::mt19937* rng) {
  std::vector<Position> p(num_vertices);
  const double side = std::sqrt(static_cast<double>(num_vertices));
  std::uniform_real_distribution<double> uniform(-side / 2, side / 2);
  for (Position& q : p) q = {uniform(*rng), uniform(*rng)};
  if (num_vertices < 2) return p;
  std::vector<Position> force(num_vertices);
  for (int it = 0; it < options.iterations; ++it) {
    const QuadTree tree(p);
    for (int v = 0; v < num_vertices; ++v) {
      force[v] = {0, 0};
      tree.AddRepulsion(v, options.theta, &force[v]);
    }
    for (const WeightedEdge& e : edges) {
      // Attraction d^2 / k along the edge.
      const double dx = p[e.v][0] - p[e.u][0], dy = p[e.v][1] - p[e.u][1];
      const double d = std::sqrt(dx * dx + dy * dy);
      force[e.u][0] += dx * d, force[e.u][1] += dy * d;
      force[e.v][0] -= dx * d, force[e.v][1] -= dy * d;
    }
    const double temperature =
        options.initial_temperature *
        (1.0 - static_cast<double>(it) / options.iterations);
    for (int v = 0; v < num_vertices; ++v) {
      const double length = std::hypot(force[v][0], force[v][1]);
      if (length == 0) continue;
      const double step = std::min(length, temperature) / length;
      p[v][0] += force[v][0] * step, p[v][1] += force[v][1] * step;
    }
  }
  return p;
}

}  // namespace

std::vector<Position> ForceDirectedLayout(const ImageGraph& graph,
                                          const ForceLayoutOptions& options) {
  if (!options.Check()) throw std::invalid_argument("bad ForceLayoutOptions");
  const int num_vertices = graph.NumVertices();
  std::vector<Position> p(num_vertices);
  std::mt19937 rng(options.seed);
  // Each connected component is laid out on its own: apart, nothing holds
  // them together, and they drift off. They are then packed in rows,
  // largest first, one edge length apart.
  const std::vector<int> label = ConnectedComponents(graph);
  const int num_components =
      num_vertices == 0 ? 0 : *std::max_element(label.begin(), label.end()) + 1;
  std::vector<std::vector<int>> components(num_components);
  std::vector<int> local(num_vertices);
  for (int v = 0; v < num_vertices; ++v) {
    local[v] = static_cast<int>(components[label[v]].size());
    components[label[v]].push_back(v);
  }
  std::vector<std::vector<WeightedEdge>> component_edges(num_components);
  for (const WeightedEdge& e : graph.Edges()) {
    component_edges[label[e.u]].push_back({local[e.u], local[e.v], e.weight});
  }
  double area = 0;
  std::vector<std::vector<Position>> layouts;
  std::vector<Position> extent;  // width and height of each component
  for (size_t c = 0; c < components.size(); ++c) {
    layouts.push_back(LayoutConnected(static_cast<int>(components[c].size()),
                                      component_edges[c], options, &rng));
    // Move the component's lower left corner to the origin.
    Position low{1e300, 1e300}, high{-1e300, -1e300};
    for (const Position& q : layouts.back()) {
      for (int i = 0; i < 2; ++i) {
        low[i] = std::min(low[i], q[i]), high[i] = std::max(high[i], q[i]);
      }
    }
    for (Position& q : layouts.back()) q = {q[0] - low[0], q[1] - low[1]};
    extent.push_back({high[0] - low[0], high[1] - low[1]});
    area += (extent.back()[0] + 1) * (extent.back()[1] + 1);
  }
  // Shelf packing into rows about as wide as the whole is high.
  const double row_width = std::sqrt(area);
  double x = 0, y = 0, row_height = 0;
  for (size_t c = 0; c < components.size(); ++c) {
    const double width = extent[c][0], height = extent[c][1];
    if (x > 0 && x + width > row_width)
      x = 0, y += row_height + 1, row_height = 0;
    for (size_t i = 0; i < components[c].size(); ++i) {
      p[components[c][i]] = {x + layouts[c][i][0], y + layouts[c][i][1]};
    }
    x += width + 1;
    row_height = std::max(row_height, height);
  }
  return p;
}

std::vector<std::array<double, 2>> LayoutInUnitSquare(
    const std::vector<std::array<double, 2>>& layout) {
  double min_x = 1e300, max_x = -1e300, min_y = 1e300, max_y = -1e300;
  for (const std::array<double, 2>& p : layout) {
    min_x = std::min(min_x, p[0]), max_x = std::max(max_x, p[0]);
    min_y = std::min(min_y, p[1]), max_y = std::max(max_y, p[1]);
  }
  const double span = std::max({max_x - min_x, max_y - min_y, 1e-9});
  std::vector<std::array<double, 2>> unit;
  for (const std::array<double, 2>& p : layout)
    unit.push_back({(p[0] - min_x) / span, (p[1] - min_y) / span});
  return unit;
}

}  // namespace tmr
