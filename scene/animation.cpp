#include "scene/animation.h"

#include "core/error.h"
#include "scene/json_pointer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace kasumi {

namespace {

constexpr int64_t kMsPerDay = 86400000;

/// Days from 1970-01-01 to the proleptic Gregorian date y-m-d (H. Hinnant, "chrono-Compatible
/// Low-Level Date Algorithms", days_from_civil).
int64_t days_from_civil(int64_t y, int64_t m, int64_t d) {
    y -= m <= 2 ? 1 : 0;
    const int64_t era = (y >= 0 ? y : y - 399) / 400;
    const int64_t yoe = y - era * 400;
    const int64_t doy = (153 * (m > 2 ? m - 3 : m + 9) + 2) / 5 + d - 1;
    const int64_t doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
    return era * 146097 + doe - 719468;
}

/// The inverse of days_from_civil (same source, civil_from_days).
void civil_from_days(int64_t z, int64_t& y, int64_t& m, int64_t& d) {
    z += 719468;
    const int64_t era = (z >= 0 ? z : z - 146096) / 146097;
    const int64_t doe = z - era * 146097;
    const int64_t yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365;
    const int64_t doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    const int64_t mp = (5 * doy + 2) / 153;
    d = doy - (153 * mp + 2) / 5 + 1;
    m = mp < 10 ? mp + 3 : mp - 9;
    y = yoe + era * 400 + (m <= 2 ? 1 : 0);
}

bool is_leap(int64_t y) {
    return (y % 4 == 0 && y % 100 != 0) || y % 400 == 0;
}

int days_in_month(int64_t y, int64_t m) {
    static const int kDays[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    return m == 2 && is_leap(y) ? 29 : kDays[m - 1];
}

/// Reads exactly `n` decimal digits at text[pos], advancing pos.
bool read_digits(const std::string& text, size_t& pos, int n, int64_t& out) {
    if (pos + static_cast<size_t>(n) > text.size())
        return false;
    out = 0;
    for (int i = 0; i < n; ++i) {
        const char c = text[pos + static_cast<size_t>(i)];
        if (c < '0' || c > '9')
            return false;
        out = out * 10 + (c - '0');
    }
    pos += static_cast<size_t>(n);
    return true;
}

bool expect_char(const std::string& text, size_t& pos, char c) {
    if (pos < text.size() && text[pos] == c) {
        ++pos;
        return true;
    }
    return false;
}

const char* kind_name(TrackKind kind) {
    switch (kind) {
        case TrackKind::Number:
            return "a number";
        case TrackKind::NumberArray:
            return "an array of numbers";
        case TrackKind::Datetime:
            return "an ISO-8601 date-time";
    }
    return "";
}

/// The kind of an animatable JSON value; false for anything else.
bool kind_of(const Json& v, TrackKind& kind, size_t& length, Datetime& datetime) {
    if (v.is_number()) {
        kind = TrackKind::Number;
        length = 1;
        return true;
    }
    if (v.is_array() && !v.empty() &&
        std::all_of(v.begin(), v.end(), [](const Json& e) { return e.is_number(); })) {
        kind = TrackKind::NumberArray;
        length = v.size();
        return true;
    }
    if (v.is_string() && parse_datetime(v.get<std::string>(), datetime)) {
        kind = TrackKind::Datetime;
        length = 1;
        return true;
    }
    return false;
}

bool is_integer_value(const Json& v) {
    if (v.is_number_integer())
        return true;
    if (v.is_number_float()) {
        const double d = v.get<double>();
        return std::isfinite(d) && d == std::floor(d) && std::abs(d) < 9.0e15;
    }
    return false;
}

Json number_json(double v, bool integral) {
    if (integral && v == std::floor(v) && std::abs(v) < 9.0e15)
        return Json(static_cast<int64_t>(v));
    return Json(v);
}

/// (1 - t) a + t b: exactly a at t = 0 and exactly b at t = 1.
double lerp(double a, double b, double t) {
    return (1.0 - t) * a + t * b;
}

Track parse_track(const JsonNode& node, const Json& root, const std::string& pointer) {
    if (pointer.empty() || pointer[0] != '/')
        node.fail("the key must be a JSON pointer into the scene, e.g. \"/sun/elevation_deg\"");
    const auto tokens = pointer_tokens(pointer);
    if (!tokens)
        node.fail("\"" + pointer + "\" is not a valid JSON pointer");
    if (!tokens->empty() && tokens->front() == "animate")
        node.fail("cannot animate the animation itself");
    const Json* found = find_value(root, *tokens);
    if (found == nullptr)
        node.fail("unknown pointer: " + pointer +
                  " does not exist in the scene (give it a value "
                  "there first)");
    const Json& current = *found;
    Track track;
    track.pointer = pointer;
    size_t length = 0;
    Datetime current_datetime;
    if (!kind_of(current, track.kind, length, current_datetime)) {
        node.fail("cannot animate " + pointer + " = " + current.dump() +
                  ": only numbers, arrays of numbers and ISO-8601 date-times interpolate");
    }
    if (!node.is_array() || node.size() == 0)
        node.fail("expected keyframes [[frame, value], ...]");
    for (const JsonNode& key : node.elements()) {
        if (!key.is_array() || key.size() != 2)
            key.fail("expected a keyframe [frame, value]");
        const JsonNode frame_node = key.child(size_t{0});
        const JsonNode value_node = key.child(size_t{1});
        Keyframe k;
        k.frame = frame_node.as_int();
        if (!track.keys.empty() && k.frame <= track.keys.back().frame) {
            frame_node.fail(
                std::string(k.frame == track.keys.back().frame ? "duplicate" : "unsorted") +
                " key frame: frames must be strictly increasing (the previous key "
                "is at frame " +
                std::to_string(track.keys.back().frame) + ")");
        }
        TrackKind kind = TrackKind::Number;
        size_t key_length = 0;
        if (!kind_of(value_node.value(), kind, key_length, k.datetime) || kind != track.kind ||
            key_length != length) {
            value_node.fail(
                std::string("type mismatch: ") + pointer + " holds " + kind_name(track.kind) +
                (track.kind == TrackKind::NumberArray ? " of length " + std::to_string(length)
                                                      : std::string()) +
                ", so must every key value");
        }
        if (kind == TrackKind::Datetime) {
            if (k.datetime.has_zone != current_datetime.has_zone)
                value_node.fail("type mismatch: every date-time of " + pointer + " must " +
                                (current_datetime.has_zone ? "give" : "omit") +
                                " a time zone, as the scene's value does");
            k.values = {static_cast<double>(k.datetime.utc_ms)};
        } else if (kind == TrackKind::Number) {
            k.values = {value_node.as_double()};
            track.integral = track.integral && is_integer_value(value_node.value());
        } else {
            for (const JsonNode& e : value_node.elements()) {
                k.values.push_back(e.as_double());
                track.integral = track.integral && is_integer_value(e.value());
            }
        }
        track.keys.push_back(std::move(k));
    }
    return track;
}

}  // namespace

bool parse_datetime(const std::string& text, Datetime& out) {
    size_t pos = 0;
    int64_t y = 0, mo = 0, d = 0, h = 0, mi = 0, s = 0, ms = 0;
    if (!read_digits(text, pos, 4, y) || !expect_char(text, pos, '-') ||
        !read_digits(text, pos, 2, mo) || !expect_char(text, pos, '-') ||
        !read_digits(text, pos, 2, d) || !expect_char(text, pos, 'T') ||
        !read_digits(text, pos, 2, h) || !expect_char(text, pos, ':') ||
        !read_digits(text, pos, 2, mi)) {
        return false;
    }
    if (expect_char(text, pos, ':')) {
        if (!read_digits(text, pos, 2, s))
            return false;
        if (expect_char(text, pos, '.')) {
            // Fractional seconds: keep milliseconds, round the rest half up.
            int64_t scale = 100;
            int digits = 0;
            double rest = 0.0, rest_scale = 0.1;
            while (pos < text.size() && text[pos] >= '0' && text[pos] <= '9') {
                const int digit = text[pos] - '0';
                if (digits < 3) {
                    ms += digit * scale;
                    scale /= 10;
                } else {
                    rest += digit * rest_scale;
                    rest_scale *= 0.1;
                }
                ++digits;
                ++pos;
            }
            if (digits == 0)
                return false;
            if (rest >= 0.5)
                ++ms;
        }
    }
    if (mo < 1 || mo > 12 || d < 1 || d > days_in_month(y, mo) || h > 23 || mi > 59 || s > 59)
        return false;
    Datetime t;
    if (pos < text.size()) {
        if (text[pos] == 'Z') {
            ++pos;
            t.has_zone = true;
        } else if (text[pos] == '+' || text[pos] == '-') {
            const int sign = text[pos] == '-' ? -1 : 1;
            ++pos;
            int64_t oh = 0, om = 0;
            if (!read_digits(text, pos, 2, oh))
                return false;
            expect_char(text, pos, ':');
            if (!read_digits(text, pos, 2, om) || oh > 23 || om > 59)
                return false;
            t.has_zone = true;
            t.offset_minutes = sign * static_cast<int>(oh * 60 + om);
        }
    }
    if (pos != text.size())
        return false;
    const int64_t local_ms =
        days_from_civil(y, mo, d) * kMsPerDay + ((h * 60 + mi) * 60 + s) * 1000 + ms;
    t.utc_ms = local_ms - static_cast<int64_t>(t.offset_minutes) * 60000;
    out = t;
    return true;
}

std::string format_datetime(const Datetime& t) {
    const int64_t local_ms = t.utc_ms + static_cast<int64_t>(t.offset_minutes) * 60000;
    int64_t days = local_ms / kMsPerDay;
    int64_t in_day = local_ms % kMsPerDay;
    if (in_day < 0) {
        in_day += kMsPerDay;
        --days;
    }
    int64_t y = 0, m = 0, d = 0;
    civil_from_days(days, y, m, d);
    const int64_t ms = in_day % 1000, sec = in_day / 1000;
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%04lld-%02lld-%02lldT%02lld:%02lld:%02lld",
                  static_cast<long long>(y), static_cast<long long>(m), static_cast<long long>(d),
                  static_cast<long long>(sec / 3600), static_cast<long long>(sec / 60 % 60),
                  static_cast<long long>(sec % 60));
    std::string text = buffer;
    if (ms != 0) {
        std::snprintf(buffer, sizeof buffer, ".%03lld", static_cast<long long>(ms));
        text += buffer;
    }
    if (t.has_zone) {
        if (t.offset_minutes == 0) {
            text += "Z";
        } else {
            const int a = std::abs(t.offset_minutes);
            std::snprintf(buffer, sizeof buffer, "%c%02d:%02d", t.offset_minutes < 0 ? '-' : '+',
                          a / 60, a % 60);
            text += buffer;
        }
    }
    return text;
}

int64_t Animation::first_frame() const {
    int64_t first = std::numeric_limits<int64_t>::max();
    for (const Track& t : tracks)
        first = std::min(first, t.keys.front().frame);
    return tracks.empty() ? 0 : first;
}

int64_t Animation::last_frame() const {
    int64_t last = std::numeric_limits<int64_t>::min();
    for (const Track& t : tracks)
        last = std::max(last, t.keys.back().frame);
    return tracks.empty() ? 0 : last;
}

Animation parse_animation(const SceneDocument& doc) {
    Animation animation;
    const Json& root = doc.json();
    if (!root.is_object() || !root.contains("animate"))
        return animation;
    const JsonNode node = JsonNode(root, doc.file()).child("animate");
    if (!node.is_object())
        node.fail("expected an object {\"/json/pointer\": [[frame, value], ...], ...}");
    for (const auto& item : node.value().items())
        animation.tracks.push_back(parse_track(node.child(item.key()), root, item.key()));
    return animation;
}

Json evaluate(const Track& track, int64_t frame) {
    const std::vector<Keyframe>& keys = track.keys;
    KASUMI_CHECK(!keys.empty());
    // The last key at or before `frame` (the first key when none is).
    const auto after = std::upper_bound(keys.begin(), keys.end(), frame,
                                        [](int64_t f, const Keyframe& k) { return f < k.frame; });
    const Keyframe& k0 = after == keys.begin() ? keys.front() : *(after - 1);
    const bool hold = after == keys.begin() || after == keys.end() || k0.frame == frame;
    const Keyframe& k1 = hold ? k0 : *after;
    // t in (0, 1) strictly between two keys; holds and exact key frames take a key's value.
    const double t =
        hold ? 0.0
             : static_cast<double>(frame - k0.frame) / static_cast<double>(k1.frame - k0.frame);
    switch (track.kind) {
        case TrackKind::Number:
            return number_json(lerp(k0.values[0], k1.values[0], t), track.integral);
        case TrackKind::NumberArray: {
            Json out = Json::array();
            for (size_t i = 0; i < k0.values.size(); ++i)
                out.push_back(number_json(lerp(k0.values[i], k1.values[i], t), track.integral));
            return out;
        }
        case TrackKind::Datetime: {
            Datetime d = k0.datetime;
            const double delta_ms = static_cast<double>(k1.datetime.utc_ms - k0.datetime.utc_ms);
            d.utc_ms = k0.datetime.utc_ms + std::llround(delta_ms * t);
            return Json(format_datetime(d));
        }
    }
    return Json();
}

std::string frame_context(const Animation& animation, int64_t frame, const std::string& message) {
    if (animation.empty())
        return std::string();
    bool key = false;
    std::string tracks;
    for (const Track& track : animation.tracks) {
        const auto after =
            std::upper_bound(track.keys.begin(), track.keys.end(), frame,
                             [](int64_t f, const Keyframe& k) { return f < k.frame; });
        const bool at_key = after != track.keys.begin() && (after - 1)->frame == frame;
        key = key || at_key;
        // The pointer itself or a value under it, as a scene error prints it ("/a/b = 2: ...",
        // "/a/b/1: ...").
        bool named = false;
        for (size_t at = message.find(track.pointer); at != std::string::npos && !named;
             at = message.find(track.pointer, at + 1)) {
            const size_t end = at + track.pointer.size();
            named = end == message.size() ||
                    std::string(" :/,)").find(message[end]) != std::string::npos;
        }
        if (!named || at_key)
            continue;
        tracks += "; " + track.pointer;
        if (after == track.keys.begin() || after == track.keys.end()) {
            const Keyframe& held =
                after == track.keys.begin() ? track.keys.front() : track.keys.back();
            tracks += " held at key frame " + std::to_string(held.frame);
        } else {
            tracks += " between key frames " + std::to_string((after - 1)->frame) + " and " +
                      std::to_string(after->frame);
        }
    }
    return std::string(" (at ") + (key ? "key frame " : "frame ") + std::to_string(frame) +
           " of /animate" + tracks + ")";
}

SceneDocument frame_document(const SceneDocument& doc, const Animation& animation, int64_t frame) {
    SceneDocument out = doc;
    if (out.json().is_object())
        out.json().erase("animate");
    for (const Track& track : animation.tracks)
        out.set(track.pointer, evaluate(track, frame), "/animate");
    return out;
}

void apply_animation(SceneDocument& doc, int64_t frame) {
    if (!doc.json().is_object() || !doc.json().contains("animate"))
        return;
    doc = frame_document(doc, parse_animation(doc), frame);
}

void reapply_overrides(SceneDocument& frame_doc, const std::vector<Override>& overrides) {
    std::vector<Override> outside;
    for (const Override& o : overrides) {
        if (o.pointer != "/animate" && o.pointer.rfind("/animate/", 0) != 0)
            outside.push_back(o);
    }
    apply_overrides(frame_doc, outside);
}

}  // namespace kasumi
