#pragma once
/// Progress on stderr: a bar redrawn in place on a terminal, a plain line per 10% otherwise,
/// nothing when quiet. Thread-safe.
#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>

namespace kasumi {

class Progress {
  public:
    Progress(std::string label, uint64_t total, bool enabled);
    ~Progress();

    void advance(uint64_t n = 1);
    void finish();

  private:
    void draw(uint64_t done);

    std::string m_label;
    uint64_t m_total;
    uint64_t m_done = 0;
    bool m_enabled;
    bool m_terminal;
    bool m_finished = false;
    int m_last_decile = -1;
    int m_last_width = -1;
    std::chrono::steady_clock::time_point m_start;
    std::mutex m_mutex;
};

}  // namespace kasumi
