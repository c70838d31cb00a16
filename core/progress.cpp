#include "core/progress.h"

#include <unistd.h>
#include <cstdio>

namespace kasumi {

Progress::Progress(std::string label, uint64_t total, bool enabled)
    : m_label(std::move(label)),
      m_total(total > 0 ? total : 1),
      m_enabled(enabled),
      m_terminal(isatty(fileno(stderr)) != 0),
      m_start(std::chrono::steady_clock::now()) {}

Progress::~Progress() {
    finish();
}

void Progress::advance(uint64_t n) {
    if (!m_enabled)
        return;
    std::lock_guard<std::mutex> lock(m_mutex);
    m_done += n;
    draw(m_done);
}

void Progress::finish() {
    if (!m_enabled)
        return;
    std::lock_guard<std::mutex> lock(m_mutex);
    if (m_finished)
        return;
    m_finished = true;
    if (m_terminal)
        std::fputc('\n', stderr);
}

void Progress::draw(uint64_t done) {
    const double fraction = static_cast<double>(done) / static_cast<double>(m_total);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - m_start).count();
    if (m_terminal) {
        constexpr int kBar = 40;
        const int filled = static_cast<int>(fraction * kBar);
        if (filled == m_last_width && done != m_total)
            return;
        m_last_width = filled;
        std::string bar(static_cast<size_t>(filled), '#');
        bar.resize(kBar, '.');
        std::fprintf(stderr, "\r%s [%s] %5.1f%% %6.1fs", m_label.c_str(), bar.c_str(),
                     100.0 * fraction, seconds);
        std::fflush(stderr);
    } else {
        const int decile = static_cast<int>(fraction * 10.0);
        if (decile == m_last_decile)
            return;
        m_last_decile = decile;
        std::fprintf(stderr, "%s: %d%% (%.1fs)\n", m_label.c_str(), decile * 10, seconds);
    }
}

}  // namespace kasumi
