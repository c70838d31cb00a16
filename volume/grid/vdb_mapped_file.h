#pragma once
/// The mapped .vdb file of the direct reader (vdb_direct.h): a read-only mapping, and a guard
/// that turns a SIGBUS from the file being cut while it is read into a failed read. Internal to
/// volume/grid.
#include <csetjmp>
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <string>

#include <setjmp.h>
#include <signal.h>

namespace kasumi::vdb_file {

/// Thrown inside the direct reader only (vdb_direct.cpp catches it): the file is not one this
/// reader handles (or is broken).
struct Declined {
    std::string why;
};
/// Throws Declined{why}.
[[noreturn]] void decline(std::string why);

/// The file, mapped read-only.
class MappedFile {
  public:
    /// Opens and maps `path`; declines (Declined) a file that cannot be opened, is not a
    /// regular non-empty file or cannot be mapped.
    explicit MappedFile(const std::string& path);
    ~MappedFile();
    MappedFile(const MappedFile&) = delete;
    MappedFile& operator=(const MappedFile&) = delete;
    const uint8_t* data() const { return m_data; }
    size_t size() const { return m_size; }
    /// The file's size now (another process may have cut it since it was mapped).
    uint64_t size_now() const;

  private:
    int m_fd = -1;
    const uint8_t* m_data = nullptr;
    size_t m_size = 0;
};

/// A read of the mapped file that survives the file being cut while it is read. Pages of a
/// mapping past the file's new end raise SIGBUS on access (even with MAP_POPULATE: truncation
/// unmaps them), so another process rewriting the .vdb killed the renderer. While a thread runs
/// `body` under a guard, a SIGBUS at an address of the mapping jumps back here instead; a
/// SIGBUS anywhere else goes to the handler that was installed before ours (by default: the
/// crash it always was). What `body` was doing is abandoned: a zip or blosc call cut short
/// leaks its small work buffers, once, on a run that then stops with an input error.
class SigbusGuard {
  public:
    SigbusGuard(const uint8_t* data, size_t size) : m_begin(data), m_end(data + size) { install(); }
    /// Runs `body`; false if it touched a page of the mapping that the file no longer has.
    /// Objects that `body` creates and a jump skips are not destroyed: keep what owns memory
    /// outside it.
    template <class Body>
    bool run(Body&& body) const {
        Active active{this, t_active, {}};
        const Restore restore{active.outer};  // also on an exception and after a jump
        t_active = &active;
        // sigsetjmp saves the signal mask (1): the handler runs with SIGBUS blocked, and a
        // jump out of it must not leave it blocked for the next fault.
        if (sigsetjmp(active.env, 1) != 0)
            return false;
        body();
        return true;
    }

  private:
    struct Active {
        const SigbusGuard* guard;
        Active* outer;
        sigjmp_buf env;
    };
    struct Restore {
        Active* outer;
        ~Restore() { t_active = outer; }
    };
    static inline thread_local Active* t_active = nullptr;
    static inline struct sigaction s_previous {};

    static void install() {
        static std::once_flag once;
        std::call_once(once, [] {
            struct sigaction action {};
            action.sa_sigaction = &SigbusGuard::handle;
            action.sa_flags = SA_SIGINFO;
            sigemptyset(&action.sa_mask);
            ::sigaction(SIGBUS, &action, &s_previous);
        });
    }
    static void handle(int signal, siginfo_t* info, void* context) {
        const Active* active = t_active;
        const auto* address = static_cast<const uint8_t*>(info->si_addr);
        if (active && address >= active->guard->m_begin && address < active->guard->m_end)
            siglongjmp(const_cast<Active*>(active)->env, 1);
        // Not ours: the previous handler, or the default action once this returns and the
        // faulting access runs again.
        if (s_previous.sa_flags & SA_SIGINFO) {
            if (s_previous.sa_sigaction) {
                s_previous.sa_sigaction(signal, info, context);
                return;
            }
        } else if (s_previous.sa_handler != SIG_DFL && s_previous.sa_handler != SIG_IGN) {
            s_previous.sa_handler(signal);
            return;
        }
        ::signal(SIGBUS, SIG_DFL);
    }

    const uint8_t* m_begin;
    const uint8_t* m_end;
};

}  // namespace kasumi::vdb_file
