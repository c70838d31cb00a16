#pragma once
/// A float image with named channels (planar, row-major, top row first) plus string metadata:
/// what the film hands to the EXR writer and the preview.
#include "core/color.h"

#include <string>
#include <utility>
#include <vector>

namespace kasumi {

struct ImageChannel {
    std::string name;  ///< EXR channel name, e.g. "R", "albedo.R", "depth.Z"
    std::vector<float> data;
};

struct Image {
    int width = 0;
    int height = 0;
    std::vector<ImageChannel> channels;
    std::vector<std::pair<std::string, std::string>>
        metadata;  ///< written as EXR string attributes
    Chromaticities chromaticities;

    Image() = default;
    Image(int w, int h) : width(w), height(h) {}

    /// Adds a zero-filled channel and returns it. The reference is invalidated by the next
    /// add_channel (the channel vector may grow): fill channels one at a time, or look them up
    /// with find() after adding them all.
    ImageChannel& add_channel(const std::string& name) {
        channels.push_back(
            ImageChannel{name, std::vector<float>(static_cast<size_t>(width) * height, 0.0f)});
        return channels.back();
    }
    const ImageChannel* find(const std::string& name) const {
        for (const auto& c : channels) {
            if (c.name == name)
                return &c;
        }
        return nullptr;
    }
    ImageChannel* find(const std::string& name) {
        for (auto& c : channels) {
            if (c.name == name)
                return &c;
        }
        return nullptr;
    }
    const std::string* find_metadata(const std::string& key) const {
        for (const auto& kv : metadata) {
            if (kv.first == key)
                return &kv.second;
        }
        return nullptr;
    }
};

}  // namespace kasumi
