// The restart journal: what the bridge promised, on disk before the ack that promises it.
// The same file format as the Python runtime's (runtime/rapid_runtime/journal.py, the
// reference; docs/runtime.md "Restarts: the journal"): text lines
//     <crc32 of the JSON, 8 hex digits> <JSON object>\n
// with records {"k":"q"|"x"|"c","id","src","asset","serial"[,"c","m"]}, {"k":"s","serial"},
// {"k":"start","serial","t"}, {"k":"stop"}. A bridge of either runtime reads the other's.
//
// Use (the manager's hook): note() each step before its ack, sync() before writing the acks
// of a batch, restore what open() recovered before reading commands, close(true) on a clean
// stop. A damaged line is skipped; the file is then reported in one log line, renamed
// <name>.damaged-<time>-<pid> and rewritten from the sound lines. Never throws: a journal
// that cannot be used is reported and open() returns nullptr. A write or sync that fails
// (full disk) is logged once until one succeeds again; the bridge goes on answering.
// Thread-safe: the manager writes under its lock, config serials come from other threads.
#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace rapid_runtime {

struct JournalEntry {
    std::string cmd_id;
    std::string src_name;
    std::string asset_name;
    std::int64_t serial = 0;
    char state = 'q';  // q accepted into the queue, x running, c finished
    std::string completion;  // "ACK_COMPLETED_OK", ... (state c)
    std::string message;  // (state c)
};

struct JournalRecovered {
    std::vector<JournalEntry> unfinished;  // in the order they were accepted
    std::vector<JournalEntry> finished;  // oldest first, the last `window`
    std::int64_t last_serial = 0;
    bool crashed = false;  // the journal did not end with a clean stop
};

// The configs' first serial of a bridge that asked for `requested` (-1: the start time,
// which stays -1 here): after a crash, above the highest the journal recorded, even one
// issued less than a second before it (receivers ignore a config whose serial did not change).
std::int64_t restart_serial(std::int64_t requested, const JournalRecovered& recovered, std::int64_t now);

class Journal {
public:
    using Log = std::function<void(const std::string&)>;

    // folder/<asset>-domain<N>.journal, locked (flock) against another bridge.
    static std::unique_ptr<Journal> open(const std::string& folder, const std::string& asset, int domain,
                                         std::size_t window, Log log, JournalRecovered& recovered);
    ~Journal();
    Journal(const Journal&) = delete;
    Journal& operator=(const Journal&) = delete;

    void start(std::int64_t serial);
    void serial(std::int64_t serial);  // a config serial issued (recorded when above the last)
    void note(const JournalEntry& entry);  // a repeated q/x step is not written again
    bool sync();  // fdatasync what was written; compacts when due; false (logged) on failure
    void close(bool clean);

    std::size_t lines() const;
    std::size_t syncs() const;  // fdatasyncs done by sync() (tests: one per batch)
    bool unsynced() const;  // records written since the last sync (tests: none when an ack goes out)
    const std::string& path() const { return path_; }
    // $RAPID_STATE_DIR, else $XDG_STATE_HOME/rapid_runtime, else ~/.local/state/rapid_runtime.
    static std::string default_dir();
    static std::string file_name(const std::string& asset, int domain);
    // One line of the file, and the record of one (false: damaged). Exposed for tests.
    static std::string line_of(const std::map<std::string, std::string>& strings,
                               const std::map<std::string, std::int64_t>& numbers);
    static bool parse_line(const std::string& raw, std::map<std::string, std::string>& strings,
                           std::map<std::string, std::int64_t>& numbers);

private:
    Journal(std::string path, int fd, std::size_t window, Log log);
    void recover(JournalRecovered& out);
    void apply(const JournalEntry& e);
    void append(const std::string& line);
    void rewrite();
    void failed(const std::string& what);  // logged once until the next success

    std::string path_;
    int fd_;
    std::size_t window_;
    Log log_;
    std::vector<JournalEntry> live_;  // accepted or running, in order (a few: the queue's)
    std::deque<JournalEntry> done_;  // the last `window` outcomes, oldest first
    std::int64_t last_serial_ = 0;
    std::size_t lines_ = 0;
    std::size_t syncs_ = 0;
    bool unsynced_ = false;
    bool failing_ = false;
    mutable std::mutex mutex_;  // the public calls; the private ones run under it
};

}  // namespace rapid_runtime
