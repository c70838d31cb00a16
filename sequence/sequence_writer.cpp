#include "sequence/sequence_writer.h"

#include <algorithm>
#include <utility>

namespace kasumi {

SequenceWriter::SequenceWriter(size_t capacity)
    : m_capacity(std::max<size_t>(1, capacity)), m_thread([this] { run(); }) {}

SequenceWriter::~SequenceWriter() {
    {
        std::lock_guard<std::mutex> lock(m_mutex);
        m_stop = true;
    }
    m_changed.notify_all();
    m_thread.join();
}

void SequenceWriter::submit(std::function<void()> task) {
    std::unique_lock<std::mutex> lock(m_mutex);
    m_changed.wait(lock, [&] { return m_error != nullptr || m_queue.size() < m_capacity; });
    if (m_error != nullptr)
        std::rethrow_exception(m_error);
    m_queue.push_back(std::move(task));
    lock.unlock();
    m_changed.notify_all();
}

void SequenceWriter::check() const {
    std::lock_guard<std::mutex> lock(m_mutex);
    if (m_error != nullptr)
        std::rethrow_exception(m_error);
}

void SequenceWriter::finish() {
    std::unique_lock<std::mutex> lock(m_mutex);
    m_changed.wait(lock, [&] { return m_queue.empty() && !m_busy; });
    if (m_error != nullptr)
        std::rethrow_exception(m_error);
}

void SequenceWriter::run() {
    std::unique_lock<std::mutex> lock(m_mutex);
    for (;;) {
        m_changed.wait(lock, [&] { return m_stop || !m_queue.empty(); });
        if (m_queue.empty())
            return;  // stopping, nothing left
        std::function<void()> task = std::move(m_queue.front());
        m_queue.pop_front();
        if (m_error != nullptr) {
            // An earlier frame failed: drop the rest (the caller sees the first error).
            m_changed.notify_all();
            continue;
        }
        m_busy = true;
        lock.unlock();
        m_changed.notify_all();  // a queue slot is free
        std::exception_ptr error;
        try {
            task();
        } catch (...) {
            error = std::current_exception();
        }
        task = nullptr;  // release what the task held (the frame's image) outside the lock
        lock.lock();
        m_busy = false;
        if (error != nullptr && m_error == nullptr)
            m_error = error;
        m_changed.notify_all();
    }
}

}  // namespace kasumi
