#pragma once
/// Reads a scene file (JSON with comments) into a validated SceneDesc. Every error names the
/// file and the JSON pointer of the offending value.
#include "core/json_node.h"
#include "render/scene.h"

#include <string>
#include <utility>
#include <vector>

namespace kasumi {

/// One --set override: a JSON pointer and the text of its new value.
struct Override {
    std::string pointer;
    std::string value;
};

/// Parses "--set" text "/json/pointer=VALUE"; throws a usage error if malformed.
Override parse_override(const std::string& text);

/// Applies overrides to a document: VALUE is read as JSON when it parses as JSON, else taken as
/// a string. The parent of the pointer must exist.
void apply_overrides(Json& root, const std::vector<Override>& overrides, const std::string& file);

/// Builds a scene from a parsed document; `file` names it in errors and sets base_dir.
SceneDesc parse_scene(const Json& root, const std::string& file);

/// Reads, overrides and parses a scene file.
SceneDesc load_scene(const std::string& path, const std::vector<Override>& overrides = {});

}  // namespace kasumi
