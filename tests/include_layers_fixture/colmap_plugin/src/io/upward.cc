// A file of the lowest layer that includes one above it: what
// include_layers.cmake must refuse (test colmap_plugin_layers.refuses_upward).
#include "merge/scene_assembly.h"
