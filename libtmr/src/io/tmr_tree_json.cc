// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// tree.json reading and writing (nlohmann::json, private to libtmr).
#include <cmath>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <type_traits>
#include <unordered_map>
#include <variant>

#include "tmr/io/atomic_file.h"
#include "tmr/partition/tmr_tree.h"
#include "tmr/util/option_table.h"

namespace tmr {
namespace {

using nlohmann::json;

KernelOrigin OriginFromName(const std::string& name) {
  for (const KernelOrigin origin :
       {KernelOrigin::kPlace, KernelOrigin::kLayer, KernelOrigin::kCarved,
        KernelOrigin::kRescue}) {
    if (name == KernelOriginName(origin)) return origin;
  }
  throw std::runtime_error("unknown kernel origin '" + name + "'");
}

json Names(const TmrTree& tree, const std::vector<int>& images) {
  json names = json::array();
  for (const int v : images) names.push_back(tree.image_names.at(v));
  return names;
}

// Every row of TmrTreeOptions::AddTo, by its name.
json Parameters(TmrTreeOptions options) {
  OptionTable table;
  options.AddTo(&table);
  json parameters = json::object();
  for (const OptionRow& row : table.rows()) {
    std::visit([&](const auto* field) { parameters[row.name] = *field; },
               row.value);
  }
  return parameters;
}

// Reads an optional value of the expected type. An integer must be a whole
// number in T's range: nlohmann's conversion of 3e41 to int is undefined
// behaviour (found by fuzz_tree_json).
template <typename T>
void Get(const json& object, const char* key, T* value) {
  if (!object.is_object() || !object.contains(key)) return;
  const json& v = object.at(key);
  if constexpr (std::is_integral_v<T> && !std::is_same_v<T, bool>) {
    if (v.is_number()) {
      const double d = v.get<double>();
      if (!(d >= static_cast<double>(std::numeric_limits<T>::min()) &&
            d <= static_cast<double>(std::numeric_limits<T>::max())) ||
          (v.is_number_float() && d != std::floor(d))) {
        throw std::runtime_error(std::string("malformed tree.json: \"") + key +
                                 "\" is not an integer in range");
      }
      *value = v.is_number_float() ? static_cast<T>(d) : v.get<T>();
      return;
    }
  }
  *value = v.get<T>();
}

// The rows that `p` names; the others keep their defaults (a tree.json of
// version 1 had nested parameters: they all stay at their defaults).
TmrTreeOptions ParametersFromJson(const json& p) {
  TmrTreeOptions o;
  OptionTable table;
  o.AddTo(&table);
  for (const OptionRow& row : table.rows()) {
    std::visit([&](auto* field) { Get(p, row.name.c_str(), field); },
               row.value);
  }
  o.exemplar.ap.seed = o.seed;
  return o;
}

}  // namespace

void WriteTmrTreeJson(const TmrTree& tree, std::ostream& out) {
  json kernels = json::array();
  for (const TmrKernelNode& node : tree.kernels) {
    json leaf_clusters = json::array();
    for (const auto& leaf : node.leaf_clusters)
      leaf_clusters.push_back(Names(tree, leaf));
    json leaf_halos = json::array();
    for (const auto& halo : node.leaf_halos)
      leaf_halos.push_back(Names(tree, halo));
    kernels.push_back({{"exemplar", tree.image_names.at(node.exemplar)},
                       {"second_image",
                        node.second_images.empty()
                            ? json(nullptr)
                            : json(tree.image_names.at(node.second_images[0]))},
                       {"second_images", Names(tree, node.second_images)},
                       {"ap_centres", Names(tree, node.ap_centres)},
                       {"exemplar_score", node.exemplar_score},
                       {"origin", KernelOriginName(node.origin)},
                       {"layer", node.layer},
                       {"kernel_images", Names(tree, node.kernel_images)},
                       {"leaf_clusters", std::move(leaf_clusters)},
                       {"leaf_halos", std::move(leaf_halos)}});
  }
  const json root = {{"format", "tmr-tree"},
                     {"version", 2},
                     {"num_images", tree.image_names.size()},
                     {"kernel_size", tree.kernel_size},
                     {"kernels", std::move(kernels)},
                     {"unclustered", Names(tree, tree.unclustered)},
                     {"parameters", Parameters(tree.options)},
                     {"timing_s",
                      {{"graphs", tree.timing.graphs_s},
                       {"kernels", tree.timing.kernels_s},
                       {"exemplars", tree.timing.exemplars_s},
                       {"image_clusters", tree.timing.image_clusters_s},
                       {"leaf_clusters", tree.timing.leaf_clusters_s},
                       {"halos", tree.timing.halos_s}}}};
  out << root.dump(1) << "\n";
}

TmrTree ReadTmrTreeJson(std::istream& in,
                        const std::vector<std::string>& image_names) {
  TmrTree tree;
  tree.image_names = image_names;
  std::unordered_map<std::string, int> index;
  for (size_t i = 0; i < image_names.size(); ++i)
    index.emplace(image_names[i], i);
  auto vertex = [&](const json& name) {
    if (!name.is_string())
      throw std::runtime_error("an image name is not a string");
    const std::string& s = name.get_ref<const std::string&>();
    const auto it = index.find(s);
    if (it != index.end()) return it->second;
    if (!image_names.empty())
      throw std::runtime_error("unknown image '" + s + "'");
    index.emplace(s, static_cast<int>(tree.image_names.size()));
    tree.image_names.push_back(s);
    return static_cast<int>(tree.image_names.size()) - 1;
  };
  auto vertices = [&](const json& names) {
    if (!names.is_array())
      throw std::runtime_error("expected a list of image names");
    std::vector<int> result;
    for (const json& name : names) result.push_back(vertex(name));
    return result;
  };
  try {
    const json root = json::parse(in);
    if (!root.is_object() || root.value("format", "") != "tmr-tree") {
      throw std::runtime_error(
          "not a tmr tree (\"format\": \"tmr-tree\" missing)");
    }
    Get(root, "kernel_size", &tree.kernel_size);
    if (root.contains("parameters"))
      tree.options = ParametersFromJson(root.at("parameters"));
    for (const json& k : root.at("kernels")) {
      TmrKernelNode node;
      node.exemplar = vertex(k.at("exemplar"));
      node.kernel_images = vertices(k.at("kernel_images"));
      if (k.contains("second_images")) {
        node.second_images = vertices(k.at("second_images"));
      } else if (k.contains("second_image") &&
                 !k.at("second_image").is_null()) {
        node.second_images = {vertex(k.at("second_image"))};
      }
      if (k.contains("ap_centres"))
        node.ap_centres = vertices(k.at("ap_centres"));
      node.exemplar_score = k.value("exemplar_score", 0.0);
      node.origin = OriginFromName(k.value("origin", "layer"));
      Get(k, "layer", &node.layer);
      for (const json& leaf : k.at("leaf_clusters"))
        node.leaf_clusters.push_back(vertices(leaf));
      if (k.contains("leaf_halos")) {
        for (const json& halo : k.at("leaf_halos"))
          node.leaf_halos.push_back(vertices(halo));
      }
      if (node.leaf_halos.empty())
        node.leaf_halos.resize(node.leaf_clusters.size());
      if (node.leaf_halos.size() != node.leaf_clusters.size())
        throw std::runtime_error("one leaf_halos list per leaf cluster");
      node.cluster_images = node.kernel_images;
      for (const auto& leaf : node.leaf_clusters) {
        node.cluster_images.insert(node.cluster_images.end(), leaf.begin(),
                                   leaf.end());
      }
      std::sort(node.cluster_images.begin(), node.cluster_images.end());
      tree.kernels.push_back(std::move(node));
    }
    tree.unclustered = vertices(root.at("unclustered"));
  } catch (const json::exception& e) {
    throw std::runtime_error(std::string("malformed tree.json: ") + e.what());
  }
  return tree;
}

std::string TmrTreeJsonPath(const std::string& folder) {
  return (std::filesystem::path(folder) / "tree.json").string();
}

bool WriteTmrTreeJsonFile(const TmrTree& tree, const std::string& folder) {
  std::ostringstream json;
  WriteTmrTreeJson(tree, json);
  return WriteFileAtomically(TmrTreeJsonPath(folder), json.str());
}

}  // namespace tmr
