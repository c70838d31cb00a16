#pragma once
/// The background writer of a frame sequence (docs/sequences.md): frame N's files are written on
/// one worker thread while frame N + 1 renders. Tasks run one at a time in the order submitted,
/// so files and log lines keep the frames' order. The queue is bounded: submit() waits while
/// `capacity` tasks are pending, so at most capacity + 1 frames' images are alive at once.
///
/// Failures: the first task that throws is remembered and every later task is dropped (not run),
/// so after a failed write of frame k no later frame reaches the disk; submit(), check() and
/// finish() rethrow that first error. Each task writes its files atomically (core/atomic_file),
/// so a failed or dropped frame leaves no file under its final name.
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>

namespace kasumi {

class SequenceWriter {
  public:
    /// Starts the worker thread; `capacity` >= 1 tasks may wait behind the one running.
    explicit SequenceWriter(size_t capacity = 1);
    /// Runs the tasks still queued (unless one failed), then joins: frames already rendered are
    /// written even when the caller unwinds from an exception. Errors are not rethrown here.
    ~SequenceWriter();
    SequenceWriter(const SequenceWriter&) = delete;
    SequenceWriter& operator=(const SequenceWriter&) = delete;

    /// Queues `task`, waiting while the queue is full. Rethrows the first failure instead of
    /// queueing when an earlier task failed.
    void submit(std::function<void()> task);

    /// Rethrows the first failure, if any (without waiting).
    void check() const;

    /// Waits until every queued task has run (or been dropped after a failure), then rethrows
    /// the first failure. The writer stays usable if nothing failed.
    void finish();

  private:
    void run();

    const size_t m_capacity;
    mutable std::mutex m_mutex;
    std::condition_variable m_changed;
    std::deque<std::function<void()>> m_queue;
    bool m_busy = false;  ///< a task is running
    bool m_stop = false;
    std::exception_ptr m_error;
    std::thread m_thread;
};

}  // namespace kasumi
