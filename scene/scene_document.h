#pragma once
/// The scene document: a scene file's JSON and the file's name, as --set, "animate", quality
/// presets and study --vary edit it before the loader (scene/scene_loader.h) reads it. Every
/// edit goes through one JSON pointer implementation (scene/json_pointer.h), and every error
/// names the file and the pointer.
#include "core/json_text.h"

#include <string>
#include <utility>
#include <vector>

namespace kasumi {

class SceneDocument {
  public:
    SceneDocument() = default;
    SceneDocument(Json json, std::string file) : m_json(std::move(json)), m_file(std::move(file)) {}

    /// Reads a scene file (JSON with comments; errors name the file, line and column).
    static SceneDocument read(const std::string& path);

    const Json& json() const { return m_json; }
    Json& json() { return m_json; }
    /// The file the document came from, as errors name it.
    const std::string& file() const { return m_file; }

    /// The value at `pointer`, or null when there is none. Throws an input error naming the
    /// file for a malformed pointer.
    const Json* find(const std::string& pointer) const;
    bool contains(const std::string& pointer) const { return find(pointer) != nullptr; }
    /// The value at `pointer`; an input error naming the file and pointer when there is none.
    const Json& get(const std::string& pointer) const;

    /// Writes `value` at `pointer` like `mkdir -p`: missing parent objects are created (an
    /// array where the next token is "-": /media/- on a scene without media), an existing value
    /// replaced, "-" as the last token appends to an array. An input error
    /// "<file>: <source> <pointer>: <why>" for a malformed pointer, an index that is not one or
    /// lies past the end, or a step into a number, string, boolean or null; `source` says who
    /// set it ("--set", "--vary"; may be empty).
    void set(const std::string& pointer, Json value, const std::string& source = "");

  private:
    [[noreturn]] void fail(const std::string& source, const std::string& pointer,
                           const std::string& why) const;

    Json m_json;
    std::string m_file;
};

/// One --set override: a JSON pointer and the text of its new value.
struct Override {
    std::string pointer;
    std::string value;
};

/// Parses "--set" text "/json/pointer=VALUE"; throws a usage error if it does not start with a
/// well-formed pointer followed by '='.
Override parse_override(const std::string& text);

/// The JSON value an override's text stands for: the text read as JSON (no comments) when it
/// parses as JSON, else the text itself as a string (`--set /render/gi=path`). A text that is
/// JSON but refused (a number beyond double range, a key given twice, deep nesting) is an input
/// error naming `file`, the --set and the position in the text.
Json override_value(const Override& o, const std::string& file);

/// Applies overrides in order with SceneDocument::set (missing parents created, "-" appends).
void apply_overrides(SceneDocument& doc, const std::vector<Override>& overrides);

}  // namespace kasumi
