#include "scene/scene_document.h"

#include "core/error.h"
#include "scene/json_pointer.h"

namespace kasumi {

SceneDocument SceneDocument::read(const std::string& path) {
    return SceneDocument(read_json_file(path), path);
}

void SceneDocument::fail(const std::string& source, const std::string& pointer,
                         const std::string& why) const {
    throw_input_error(m_file + ": " + (source.empty() ? "" : source + " ") + pointer + ": " + why);
}

const Json* SceneDocument::find(const std::string& pointer) const {
    const auto tokens = pointer_tokens(pointer);
    if (!tokens)
        fail("", pointer, "invalid JSON pointer");
    return find_value(m_json, *tokens);
}

const Json& SceneDocument::get(const std::string& pointer) const {
    const Json* value = find(pointer);
    if (value == nullptr)
        fail("", pointer, "does not exist in the scene");
    return *value;
}

void SceneDocument::set(const std::string& pointer, Json value, const std::string& source) {
    const auto tokens = pointer_tokens(pointer);
    if (!tokens)
        fail(source, pointer, "invalid JSON pointer");
    const std::string why = write_value(m_json, *tokens, std::move(value));
    if (!why.empty())
        fail(source, pointer, why);
}

Override parse_override(const std::string& text) {
    const auto eq = text.find('=');
    if (text.empty() || text[0] != '/' || eq == std::string::npos) {
        throw Error(ErrorKind::Usage, "--set expects /json/pointer=VALUE, got \"" + text + "\"");
    }
    Override o{text.substr(0, eq), text.substr(eq + 1)};
    if (!pointer_tokens(o.pointer))
        throw Error(ErrorKind::Usage, "--set " + o.pointer + ": invalid JSON pointer");
    return o;
}

Json override_value(const Override& o, const std::string& file) {
    // Not JSON: a word (`--set /render/gi=path`).
    auto value = parse_json_if_json(o.value, file + ": --set " + o.pointer);
    return value ? std::move(*value) : Json(o.value);
}

void apply_overrides(SceneDocument& doc, const std::vector<Override>& overrides) {
    for (const Override& o : overrides)
        doc.set(o.pointer, override_value(o, doc.file()), "--set");
}

}  // namespace kasumi
