#pragma once
/// Reads a scene file (JSON with comments) into a validated SceneDesc. Every error names the
/// file and the JSON pointer of the offending value.
#include "core/json_node.h"
#include "scene/animation.h"
#include "scene/scene.h"
#include "scene/scene_document.h"

#include <map>
#include <string>
#include <utility>
#include <vector>

namespace kasumi {

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

/// A scene file as every command reads it: the file with the command line's overrides
/// applied (missing parents created), its animation, and the document and scene of any frame.
class SceneSource {
  public:
    /// Reads `path` and applies `overrides`, then reads "animate" (input errors name the file).
    SceneSource(const std::string& path, std::vector<Override> overrides = {});
    /// The same from a document already read (the Python module's Scene.from_dict); its file()
    /// names it in errors and its directory resolves relative file names.
    SceneSource(SceneDocument document, std::vector<Override> overrides);

    /// The overridden document, "animate" still in it.
    const SceneDocument& document() const { return m_document; }
    const Animation& animation() const { return m_animation; }
    const std::vector<Override>& overrides() const { return m_overrides; }

    /// The document of `frame`: the animation evaluated, then the overrides outside /animate
    /// applied again (reapply_overrides), so a value given on the command line wins.
    SceneDocument frame_document(int64_t frame) const;

    /// The scene of `frame` (parse_scene of frame_document). An input error in an animated
    /// scene says where the frame lies among the key frames (frame_context).
    SceneDesc scene(int64_t frame = 0, ElementCache* cache = nullptr) const;

    /// parse_scene of a document of this source's file (frame_document's), with the error
    /// context of `frame`.
    SceneDesc parse(const Json& doc, int64_t frame, ElementCache* cache = nullptr) const;

    /// The key frames of every track, ascending, without repeats.
    std::vector<int64_t> key_frames() const;

  private:
    std::vector<Override> m_overrides;
    SceneDocument m_document;
    Animation m_animation;
};

/// Reads, overrides and parses a scene file at `frame` (0: an animated scene's frame 0):
/// SceneSource(path, overrides).scene(frame).
SceneDesc load_scene(const std::string& path, const std::vector<Override>& overrides = {},
                     int64_t frame = 0);

}  // namespace kasumi
