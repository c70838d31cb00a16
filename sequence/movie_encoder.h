#pragma once
/// An H.264 movie written by Debian's `ffmpeg` (libx264, yuv420p, MP4) from 8-bit display RGB
/// frames piped to its standard input. The movie appears under its final name only when ffmpeg
/// succeeded: it is encoded to a temporary file beside it (core/atomic_file.h) and renamed.
#include "core/atomic_file.h"

#include <sys/types.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace kasumi {

/// The full path of the first executable `program` in the directories of $PATH, or empty.
std::string find_on_path(const std::string& program);

/// One movie being encoded. Frames must all be width x height; yuv420p needs even dimensions,
/// so an odd last column or row is repeated (the movie is even_up(width) x even_up(height)).
class MovieEncoder {
  public:
    /// Starts ffmpeg writing `path` at `fps` frames per second (in (0, 1000]). Throws
    /// ErrorKind::Usage naming the Debian package `ffmpeg` if no ffmpeg is on $PATH, and
    /// ErrorKind::Output naming `path` if its temporary cannot be created or ffmpeg not started.
    MovieEncoder(const std::string& path, int width, int height, double fps);
    /// Unfinished (an exception unwinds): stops ffmpeg and removes the temporary.
    ~MovieEncoder();
    MovieEncoder(const MovieEncoder&) = delete;
    MovieEncoder& operator=(const MovieEncoder&) = delete;

    /// Appends one frame of packed RGB bytes, width * height * 3 of them, top row first.
    /// Throws ErrorKind::Output naming the movie if ffmpeg stopped reading.
    void add_frame(const std::vector<uint8_t>& rgb);

    /// Ends the stream, waits for ffmpeg and renames the movie into place. Throws
    /// ErrorKind::Output naming the movie and ffmpeg's exit status if it failed.
    void finish();

    int movie_width() const { return m_width + (m_width & 1); }
    int movie_height() const { return m_height + (m_height & 1); }
    size_t frames() const { return m_frames; }

  private:
    void write_all(const uint8_t* data, size_t size);
    int close_and_wait();

    std::unique_ptr<AtomicFile> m_file;
    int m_width = 0;
    int m_height = 0;
    int m_pipe = -1;  ///< ffmpeg's standard input
    pid_t m_pid = -1;
    size_t m_frames = 0;
    std::vector<uint8_t> m_padded;  ///< one frame with the odd column and row repeated
};

}  // namespace kasumi
