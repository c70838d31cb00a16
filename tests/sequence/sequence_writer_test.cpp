// The background writer of a sequence: tasks run in submission order, finish() and the
// destructor wait for every queued task, and the first failure is rethrown while every later
// task is dropped.
#include "sequence/sequence_writer.h"

#include "core/error.h"

#include <gtest/gtest.h>

#include <atomic>
#include <future>
#include <vector>

namespace kasumi {
namespace {

TEST(SequenceWriter, RunsTasksInOrderAndFinishWaitsForAll) {
    for (const size_t capacity : {size_t{1}, size_t{3}}) {
        std::vector<int> done;  // touched by the worker only until finish()
        SequenceWriter writer(capacity);
        for (int i = 0; i < 50; ++i)
            writer.submit([&done, i] { done.push_back(i); });
        writer.finish();
        ASSERT_EQ(done.size(), 50u) << "capacity " << capacity;
        for (int i = 0; i < 50; ++i)
            EXPECT_EQ(done[static_cast<size_t>(i)], i);
        // Usable again after finish().
        writer.submit([&done] { done.push_back(50); });
        writer.finish();
        EXPECT_EQ(done.size(), 51u);
    }
}

TEST(SequenceWriter, DestructorRunsWhatIsQueued) {
    std::atomic<int> done{0};
    {
        SequenceWriter writer(4);
        for (int i = 0; i < 20; ++i)
            writer.submit([&done] { ++done; });
        // No finish(): as when run_sequence unwinds from an error after rendering frames.
    }
    EXPECT_EQ(done.load(), 20);
}

TEST(SequenceWriter, FirstFailureIsRethrownAndLaterTasksAreDropped) {
    std::vector<int> done;
    // The first task holds the worker until all six are queued: without the gate the worker may
    // reach task 2 while the loop still submits, and submit() then rethrows (correctly, but
    // not what this test is about).
    std::promise<void> all_queued;
    std::shared_future<void> gate = all_queued.get_future().share();
    SequenceWriter writer(8);
    for (int i = 0; i < 6; ++i) {
        writer.submit([&done, i, gate] {
            if (i == 0)
                gate.wait();
            if (i == 2)
                throw_output_error("out/f.0002.exr: disk full");
            if (i == 4)
                throw_output_error("out/f.0004.exr: a later failure, never reached");
            done.push_back(i);
        });
    }
    all_queued.set_value();
    try {
        writer.finish();
        ADD_FAILURE() << "finish() did not rethrow the failure";
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::Output);
        EXPECT_NE(std::string(e.what()).find("out/f.0002.exr: disk full"), std::string::npos)
            << e.what();
    }
    EXPECT_EQ(done, (std::vector<int>{0, 1}));
    EXPECT_THROW(writer.check(), Error);
    EXPECT_THROW(writer.submit([&done] { done.push_back(99); }), Error);
    EXPECT_THROW(writer.finish(), Error);
    EXPECT_EQ(done, (std::vector<int>{0, 1}));
}

}  // namespace
}  // namespace kasumi
