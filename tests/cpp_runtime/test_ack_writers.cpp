// The ack writers' generations (runtime/cpp/dds/include/rapid_runtime/dds/ack_writers.hpp),
// on plain numbers for writers: what is dealt to which writer, and when a writer is deleted.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <rapid_runtime/dds/ack_writers.hpp>

using rapid_runtime::dds::ack_generation_size;
using rapid_runtime::dds::ack_key;
using rapid_runtime::dds::AckWriters;

namespace {

// Writers are numbered 1, 2, ... in the order made; deleted ones are recorded.
struct AckLedger {
    std::mutex mutex;
    int made = 0;
    std::vector<int> deleted;

    AckWriters<int>::Make make() {
        return [this] {
            std::lock_guard<std::mutex> lock(mutex);
            return ++made;
        };
    }
    AckWriters<int>::Destroy destroy() {
        return [this](int w) {
            std::lock_guard<std::mutex> lock(mutex);
            deleted.push_back(w);
        };
    }
    std::vector<int> gone() {
        std::lock_guard<std::mutex> lock(mutex);
        auto out = deleted;
        std::sort(out.begin(), out.end());
        return out;
    }
};

std::string cmd_key(int n) { return ack_key("Ground", "K10Red", "c" + std::to_string(n)); }

// The worker deletes on its own thread: wait until it has (bounded), then compare.
std::vector<int> acks_gone_when(AckLedger& ledger, const std::vector<int>& expected) {
    for (int i = 0; i < 2000 && ledger.gone() != expected; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(5));
    return ledger.gone();
}

}  // namespace

TEST(AckWriters, GenerationSizeIsAQuarterOfTheWindowAtLeast256) {
    EXPECT_EQ(ack_generation_size(4096), 1024u);
    EXPECT_EQ(ack_generation_size(16), 256u);
    EXPECT_EQ(ack_generation_size(1), 256u);
}

TEST(AckWriters, KeysKeepTheirPartsApart) {
    EXPECT_NE(ack_key("a", "bc", "d"), ack_key("ab", "c", "d"));
    EXPECT_NE(ack_key("a", "b", "cd"), ack_key("a", "bc", "d"));
    EXPECT_EQ(ack_key("a", "b", "c"), ack_key("a", "b", "c"));
}

TEST(AckWriters, CommandsAreDealtInBlocksAndEachKeepsItsWriter) {
    AckLedger ledger;
    AckWriters<int> acks(ledger.make(), 4, ledger.destroy());
    std::vector<int> writer_of;
    for (int n = 0; n < 12; ++n) writer_of.push_back(acks.writer_for(cmd_key(n)));
    EXPECT_EQ(writer_of, (std::vector<int>{1, 1, 1, 1, 2, 2, 2, 2, 3, 3, 3, 3}));
    // every later ack of a command goes through the writer that took it
    EXPECT_EQ(acks.writer_for(cmd_key(1)), 1);
    EXPECT_EQ(acks.writer_for(cmd_key(6)), 2);
    std::vector<int> live = acks.writers();
    std::sort(live.begin(), live.end());
    EXPECT_EQ(live, (std::vector<int>{1, 2, 3}));
    EXPECT_EQ(acks.deleted(), 0u);  // nothing retired, nothing deleted
}

TEST(AckWriters, AnOldGenerationGoesOnceAllItsCommandsAreRetired) {
    AckLedger ledger;
    AckWriters<int> acks(ledger.make(), 4, ledger.destroy());
    for (int n = 0; n < 9; ++n) acks.writer_for(cmd_key(n));  // writers 1 (0-3), 2 (4-7), 3 (8)
    for (int n = 0; n < 3; ++n) acks.retire(cmd_key(n));
    EXPECT_EQ(acks.deleted(), 0u);  // one of writer 1's commands still kept
    acks.retire(cmd_key(3));
    EXPECT_EQ(acks_gone_when(ledger, {1}), (std::vector<int>{1}));
    acks.retire(cmd_key(3));  // retired again, or never written: nothing happens
    acks.retire(cmd_key(99));
    // a long command keeps its old generation alive; the current one is never deleted
    for (int n = 4; n < 7; ++n) acks.retire(cmd_key(n));
    acks.retire(cmd_key(8));
    EXPECT_EQ(acks.deleted(), 1u);
    EXPECT_EQ(acks.writer_for(cmd_key(7)), 2);  // (its late acks still through writer 2)
    acks.retire(cmd_key(7));
    EXPECT_EQ(acks_gone_when(ledger, {1, 2}), (std::vector<int>{1, 2}));
    EXPECT_EQ(acks.deleted(), 2u);
    // a cmdId sent again after it was retired is a new command: the current generation's
    EXPECT_EQ(acks.writer_for(cmd_key(0)), 3);
}

TEST(AckWriters, AGenerationTurnedWithNothingLiveIsDeletedAtOnce) {
    AckLedger ledger;
    AckWriters<int> acks(ledger.make(), 2, ledger.destroy());
    acks.writer_for(cmd_key(0));
    acks.writer_for(cmd_key(1));
    acks.retire(cmd_key(0));
    acks.retire(cmd_key(1));
    EXPECT_EQ(acks.deleted(), 0u);  // still current
    EXPECT_EQ(acks.writer_for(cmd_key(2)), 2);
    EXPECT_EQ(acks_gone_when(ledger, {1}), (std::vector<int>{1}));
}

TEST(AckWriters, TheNextWriterIsMadeHalfAGenerationEarly) {
    AckLedger ledger;
    AckWriters<int> acks(ledger.make(), 4, ledger.destroy());
    acks.writer_for(cmd_key(0));
    acks.writer_for(cmd_key(1));
    EXPECT_EQ(acks.created(), 1u);
    acks.writer_for(cmd_key(2));  // half the generation taken: the worker makes the next
    for (int i = 0; i < 2000 && acks.created() < 2; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(5));
    EXPECT_EQ(acks.created(), 2u);
    acks.writer_for(cmd_key(3));
    EXPECT_EQ(acks.writer_for(cmd_key(4)), 2);  // the one made early
    EXPECT_EQ(acks.created(), 2u);
}

TEST(AckWriters, CloseDeletesTheWriterMadeEarlyAndLeavesTheLiveOnes) {
    AckLedger ledger;
    {
        AckWriters<int> acks(ledger.make(), 2, ledger.destroy());
        acks.writer_for(cmd_key(0));
        acks.writer_for(cmd_key(1));  // half of 2 taken: the next is made
        for (int i = 0; i < 2000 && acks.created() < 2; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(5));
        acks.close();
        acks.close();  // idempotent
    }
    EXPECT_EQ(ledger.made, 2);
    EXPECT_EQ(ledger.gone(), (std::vector<int>{2}));  // writer 1 is live: its owner deletes it
}

TEST(AckWriters, AWriterNotMadeEarlyIsMadeWhenTheGenerationTurns) {
    AckLedger ledger;
    int failures = 1;  // the worker's attempt fails
    AckWriters<int> acks(
        [&] {
            if (ledger.made == 1 && failures > 0) {
                --failures;
                throw std::runtime_error("no writer");
            }
            return ledger.make()();
        },
        2, ledger.destroy());
    acks.writer_for(cmd_key(0));
    acks.writer_for(cmd_key(1));
    EXPECT_EQ(acks.writer_for(cmd_key(2)), 2);
    EXPECT_EQ(failures, 0);
}
