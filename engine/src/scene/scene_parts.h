#pragma once
// Parsers for the structured parts of a scene file (fabrics, colliders, pins). Private to the engine.
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "drape/scene/scene.h"

namespace drape {

// The default fabric: the preset named by fabric.preset with every fabric.* override applied.
Fabric resolveDefaultFabric(const Settings& settings);

// "panel_fabrics": {"front": "denim", ...}: every name must be a panel of the pattern.
std::map<std::string, Fabric> parsePanelFabrics(const nlohmann::json& j, const Pattern& pattern,
                                                const std::string& where);

// "colliders": [{"type": "sphere", "center": [x, y, z], "radius": r}, {"type": "box", "min": [..], "max": [..]}]
std::vector<Collider> parseColliders(const nlohmann::json& j, const std::string& where);

// "pins": [{"panel": "p", "edge": 2}, {"panel": "p", "edge_label": "waist"}, {"region": {"min": [..], "max": [..]}},
//          {"vertices": [12, 40], "at": [[x, y, z], [x, y, z]]}] ("at" optional: the placed positions, metres)
std::vector<PinSpec> parsePins(const nlohmann::json& j, const Pattern& pattern, const std::string& where);

}  // namespace drape
