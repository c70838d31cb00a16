#pragma once
/// Keyframed scene values: the top-level "animate" object of a scene maps JSON pointers to
/// keyframes [[frame, value], ...]. A frame's document is the scene with every animated value
/// replaced by its interpolation, then parsed like any scene (docs/sequences.md).
///
/// Values are numbers, arrays of numbers (interpolated elementwise) or ISO-8601 date-times
/// (interpolated in time). Between two keys the value is linear in the frame number; before the
/// first key and after the last one it holds the nearest key's value.
#include "core/json_node.h"
#include "scene/scene_document.h"

#include <cstdint>
#include <string>
#include <vector>

namespace kasumi {

/// An instant read from ISO-8601 text "YYYY-MM-DDTHH:MM[:SS[.fff]][Z|±HH:MM|±HHMM]".
struct Datetime {
    int64_t utc_ms = 0;      ///< milliseconds since 1970-01-01T00:00:00Z (local, when no zone)
    bool has_zone = false;   ///< the text gave Z or an offset
    int offset_minutes = 0;  ///< east of UTC; 0 without a zone
};

/// Parses ISO-8601 date-time text; false if `text` is not one (the calendar date is checked).
bool parse_datetime(const std::string& text, Datetime& out);

/// Formats an instant in the offset it carries: "2026-06-21T18:00:00+02:00", with ".fff" only
/// when the milliseconds are non-zero, "Z" for a zero offset given as Z or +00:00, nothing without
/// a zone.
std::string format_datetime(const Datetime& t);

enum class TrackKind {
    Number,       ///< a JSON number
    NumberArray,  ///< an array of numbers of one length
    Datetime,     ///< an ISO-8601 date-time string
};

struct Keyframe {
    int64_t frame = 0;
    std::vector<double> values;  ///< the number(s); for a date-time, utc_ms
    Datetime datetime;           ///< Datetime tracks only
};

/// The keyframes of one animated JSON pointer, frames strictly increasing.
struct Track {
    std::string pointer;  ///< RFC 6901 pointer into the scene document
    TrackKind kind = TrackKind::Number;
    std::vector<Keyframe> keys;
    bool integral = true;  ///< every key value is an integer: exact results are written as such
};

struct Animation {
    std::vector<Track> tracks;
    bool empty() const { return tracks.empty(); }
    /// First and last key frame over all tracks (0, 0 when empty).
    int64_t first_frame() const;
    int64_t last_frame() const;
};

/// Reads the document's "animate" (absent: an empty Animation). Every pointer must name an
/// existing value of the document outside /animate, the key frames must be integers in strictly
/// increasing order, and every key value must have the animated value's type (a number, an
/// array of as many numbers, a date-time string with or without a zone like the others). Errors
/// are input errors naming the file and the JSON pointer of the offending keyframe.
Animation parse_animation(const SceneDocument& doc);

/// The value of `track` at `frame`: linear between the keys around it, the nearest key's value
/// outside them; a key's own value exactly at a key frame.
Json evaluate(const Track& track, int64_t frame);

/// Where `frame` lies in `animation`, appended to an error in that frame's document (empty
/// without tracks). `kasumi check` names key frames " (at key frame 10 of /animate)"; any other
/// frame reads " (at frame 7 of /animate)", and either adds each animated pointer that
/// `message` names (it or a value under it) with its keys around the frame:
/// "; /media/0/phase/g between key frames 5 and 10" (or "held at key frame 10", outside them).
std::string frame_context(const Animation& animation, int64_t frame, const std::string& message);

/// The document of `frame`: `doc` without "animate", each track's value written at its pointer.
SceneDocument frame_document(const SceneDocument& doc, const Animation& animation, int64_t frame);

/// In place: parse_animation then frame_document (a no-op without "animate").
void apply_animation(SceneDocument& doc, int64_t frame);

/// Overrides applied to a frame's document after the animation: each --set whose pointer is
/// outside /animate (those edit the keyframes, before evaluation) is applied again, so a value
/// given on the command line wins over keyframes of the same pointer.
void reapply_overrides(SceneDocument& frame_doc, const std::vector<Override>& overrides);

}  // namespace kasumi
