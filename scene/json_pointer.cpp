#include "scene/json_pointer.h"

namespace kasumi {

std::optional<std::vector<std::string>> pointer_tokens(const std::string& pointer) {
    std::vector<std::string> tokens;
    if (pointer.empty())
        return tokens;
    if (pointer[0] != '/')
        return std::nullopt;
    for (size_t i = 0; i < pointer.size(); ++i) {
        const char c = pointer[i];
        if (c == '/') {
            tokens.emplace_back();
        } else if (c == '~') {
            const char next = i + 1 < pointer.size() ? pointer[i + 1] : '\0';
            if (next != '0' && next != '1')
                return std::nullopt;
            tokens.back() += next == '0' ? '~' : '/';
            ++i;
        } else {
            tokens.back() += c;
        }
    }
    return tokens;
}

std::string pointer_from_tokens(const std::vector<std::string>& tokens) {
    std::string pointer;
    for (const std::string& token : tokens)
        pointer += "/" + json_pointer_escape(token);
    return pointer;
}

std::optional<size_t> array_index(const std::string& token) {
    // At most 9 digits: no array in a 64 MiB scene is longer, and the value fits any size_t.
    if (token.empty() || token.size() > 9 ||
        token.find_first_not_of("0123456789") != std::string::npos ||
        (token.size() > 1 && token[0] == '0')) {
        return std::nullopt;
    }
    return static_cast<size_t>(std::stoul(token));
}

const Json* find_value(const Json& root, const std::vector<std::string>& tokens) {
    const Json* node = &root;
    for (const std::string& token : tokens) {
        if (node->is_object()) {
            const auto it = node->find(token);
            if (it == node->end())
                return nullptr;
            node = &*it;
        } else if (node->is_array()) {
            const auto index = array_index(token);
            if (!index || *index >= node->size())
                return nullptr;
            node = &(*node)[*index];
        } else {
            return nullptr;
        }
    }
    return node;
}

std::string write_value(Json& root, const std::vector<std::string>& tokens, Json value) {
    Json* node = &root;
    for (size_t i = 0; i < tokens.size(); ++i) {
        const std::string& token = tokens[i];
        const bool last = i + 1 == tokens.size();
        const std::string here =
            i == 0 ? "/" : pointer_from_tokens({tokens.begin(), tokens.begin() + i});
        if (node->is_object()) {
            const auto it = node->find(token);
            if (last) {
                (*node)[token] = std::move(value);
                return {};
            }
            // A missing parent is an object, or an array when the next token appends ("-").
            const bool append_next = tokens[i + 1] == "-";
            node = it != node->end()
                       ? &*it
                       : &((*node)[token] = append_next ? Json::array() : Json::object());
        } else if (node->is_array()) {
            if (token == "-" && last) {
                node->push_back(std::move(value));
                return {};
            }
            const auto index = array_index(token);
            if (!index)
                return "\"" + token + "\" is not an array index (0, 1, ... or - to append)";
            if (*index >= node->size()) {
                return "index " + token + " is past the end of " + here + " (" +
                       std::to_string(node->size()) + " elements; - appends)";
            }
            node = &(*node)[*index];
            if (last) {
                *node = std::move(value);
                return {};
            }
        } else {
            return here + " is not an object or array";
        }
    }
    root = std::move(value);
    return {};
}

}  // namespace kasumi
