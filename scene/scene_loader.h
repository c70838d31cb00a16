#pragma once
/// Reads a scene file (JSON with comments) into a validated SceneDesc. Every error names the
/// file and the JSON pointer of the offending value.
#include "core/json_node.h"
#include "scene/scene.h"

#include <map>
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

/// Reuses parsed scene elements across parse_scene calls (the frames of a sequence,
/// sequence/sequence.h): each returns what parse_shape, parse_light or parse_medium would for
/// `node`, reading mesh, IES and grid files only when it has no copy yet.
class ElementCache {
  public:
    virtual ~ElementCache() = default;
    virtual Shape shape(const JsonNode& node, const std::map<std::string, uint32_t>& materials,
                        const std::string& base_dir) = 0;
    virtual Light light(const JsonNode& node, size_t index) = 0;
    virtual Medium medium(const JsonNode& node, size_t index, const std::string& base_dir) = 0;
};

/// Builds a scene from a parsed document; `file` names it in errors and sets base_dir. The
/// document must not hold "animate" (see scene/animation.h). With `cache`, shapes, lights and
/// media come from it.
SceneDesc parse_scene(const Json& root, const std::string& file, ElementCache* cache = nullptr);

/// Reads, overrides and parses a scene file; an animated scene gives its frame 0
/// (scene/animation.h: the overrides win over keyframes of the same pointer).
SceneDesc load_scene(const std::string& path, const std::vector<Override>& overrides = {});

}  // namespace kasumi
