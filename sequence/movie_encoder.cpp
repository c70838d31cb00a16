#include "sequence/movie_encoder.h"

#include "core/error.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>

extern char** environ;

namespace kasumi {

namespace {

std::string format_fps(double fps) {
    char text[32];
    std::snprintf(text, sizeof text, "%.6g", fps);
    return text;
}

/// Blocks SIGPIPE on this thread while it lives, so a write to a pipe whose reader died returns
/// EPIPE instead of killing the process; a SIGPIPE raised meanwhile is consumed, not delivered.
class SigpipeBlock {
  public:
    SigpipeBlock() {
        sigemptyset(&m_pipe);
        sigaddset(&m_pipe, SIGPIPE);
        pthread_sigmask(SIG_BLOCK, &m_pipe, &m_old);
    }
    ~SigpipeBlock() {
        sigset_t pending;
        sigpending(&pending);
        if (sigismember(&pending, SIGPIPE) == 1) {
            const timespec now{0, 0};
            sigtimedwait(&m_pipe, nullptr, &now);
        }
        pthread_sigmask(SIG_SETMASK, &m_old, nullptr);
    }
    SigpipeBlock(const SigpipeBlock&) = delete;
    SigpipeBlock& operator=(const SigpipeBlock&) = delete;

  private:
    sigset_t m_pipe;
    sigset_t m_old;
};

/// How a child that did not succeed ended, from its waitpid status.
std::string status_text(int status) {
    if (WIFEXITED(status))
        return "exited with status " + std::to_string(WEXITSTATUS(status));
    if (WIFSIGNALED(status))
        return "was killed by signal " + std::to_string(WTERMSIG(status));
    return "ended abnormally";
}

}  // namespace

std::string find_on_path(const std::string& program) {
    const char* path = std::getenv("PATH");
    if (path == nullptr)
        return {};
    const std::string dirs = path;
    size_t start = 0;
    while (start <= dirs.size()) {
        size_t end = dirs.find(':', start);
        if (end == std::string::npos)
            end = dirs.size();
        // An empty entry means the current directory (POSIX).
        const std::string dir = end == start ? "." : dirs.substr(start, end - start);
        const std::string candidate = dir + "/" + program;
        if (::access(candidate.c_str(), X_OK) == 0)
            return candidate;
        start = end + 1;
    }
    return {};
}

MovieEncoder::MovieEncoder(const std::string& path, int width, int height, double fps)
    : m_width(width), m_height(height) {
    if (width <= 0 || height <= 0 || !(fps > 0.0 && fps <= 1000.0))
        throw Error(ErrorKind::Runtime, path + ": a movie needs a positive size and fps");
    const std::string ffmpeg = find_on_path("ffmpeg");
    if (ffmpeg.empty()) {
        throw Error(ErrorKind::Usage,
                    path +
                        ": no ffmpeg on PATH; the movie is encoded by ffmpeg (H.264): install "
                        "the Debian package ffmpeg (apt-get install ffmpeg)");
    }
    m_file = std::make_unique<AtomicFile>(path);
    const std::vector<std::string> args = {
        ffmpeg, "-hide_banner", "-loglevel", "error", "-y", "-f", "rawvideo", "-pix_fmt", "rgb24",
        "-video_size", std::to_string(movie_width()) + "x" + std::to_string(movie_height()),
        "-framerate", format_fps(fps), "-i", "pipe:0", "-an", "-c:v", "libx264", "-pix_fmt",
        "yuv420p",
        // Display RGB in, BT.709 out, tagged so players decode it as the previews look.
        "-colorspace", "bt709", "-color_primaries", "bt709", "-color_trc", "iec61966-2-1",
        "-movflags", "+faststart", "-f", "mp4", m_file->temp_path()};
    std::vector<char*> argv;
    for (const std::string& a : args)
        argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);

    int fds[2];
    if (::pipe2(fds, O_CLOEXEC) != 0)
        throw_output_error(path + ": cannot create a pipe to ffmpeg: " + std::strerror(errno));
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, fds[0], 0);
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
    const int err = posix_spawn(&m_pid, ffmpeg.c_str(), &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    ::close(fds[0]);
    if (err != 0) {
        ::close(fds[1]);
        m_pid = -1;
        throw_output_error(path + ": cannot start " + ffmpeg + ": " + std::strerror(err));
    }
    m_pipe = fds[1];
    m_padded.resize(static_cast<size_t>(movie_width()) * movie_height() * 3);
}

MovieEncoder::~MovieEncoder() {
    if (m_pid > 0) {
        ::kill(m_pid, SIGTERM);
        close_and_wait();
    }
    // m_file's destructor removes the temporary: no partial movie under any name.
}

void MovieEncoder::write_all(const uint8_t* data, size_t size) {
    const SigpipeBlock block;
    while (size > 0) {
        const ssize_t n = ::write(m_pipe, data, size);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0) {
            const std::string reason = std::strerror(errno);
            throw_output_error(m_file->path() + ": ffmpeg " + status_text(close_and_wait()) +
                               " before reading every frame (" + reason +
                               "); its messages are above");
        }
        data += n;
        size -= static_cast<size_t>(n);
    }
}

void MovieEncoder::add_frame(const std::vector<uint8_t>& rgb) {
    const size_t row = static_cast<size_t>(m_width) * 3;
    KASUMI_CHECK(rgb.size() == row * static_cast<size_t>(m_height));
    if (movie_width() == m_width && movie_height() == m_height) {
        write_all(rgb.data(), rgb.size());
    } else {
        const size_t padded_row = static_cast<size_t>(movie_width()) * 3;
        for (int y = 0; y < movie_height(); ++y) {
            const uint8_t* from = rgb.data() + row * static_cast<size_t>(std::min(y, m_height - 1));
            uint8_t* to = m_padded.data() + padded_row * static_cast<size_t>(y);
            std::memcpy(to, from, row);
            if (movie_width() != m_width)
                std::memcpy(to + row, to + row - 3, 3);
        }
        write_all(m_padded.data(), m_padded.size());
    }
    ++m_frames;
}

int MovieEncoder::close_and_wait() {
    if (m_pipe >= 0) {
        ::close(m_pipe);
        m_pipe = -1;
    }
    int status = 0;
    while (::waitpid(m_pid, &status, 0) < 0 && errno == EINTR) {
    }
    m_pid = -1;
    return status;
}

void MovieEncoder::finish() {
    const int status = close_and_wait();
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
        throw_output_error(m_file->path() + ": ffmpeg " + status_text(status) +
                           "; its messages are above");
    m_file->commit();
}

}  // namespace kasumi
