// The C++ runtime's journal (runtime/cpp/src/journal.cpp) driven from tests/field/test_restart.py:
//   probe read DIR WINDOW   open the journal, print what it recovered (one journal line each:
//                           {"k":"r","crashed","serial"}, then the unfinished, then the finished),
//                           the log lines prefixed "log ", and leave without a stop record
//   probe write DIR         start(200), q cpp-1, x cpp-2, c cpp-3 (a UTF-8 message), sync, crash
#include <unistd.h>

#include <cstdio>
#include <string>

#include "rapid_runtime/journal.hpp"

using rapid_runtime::Journal;
using rapid_runtime::JournalEntry;
using rapid_runtime::JournalRecovered;

static void print(const JournalEntry& e) {
    std::map<std::string, std::string> s{{"k", std::string(1, e.state)}, {"id", e.cmd_id}, {"src", e.src_name},
                                         {"asset", e.asset_name}};
    if (e.state == 'c') {
        s["c"] = e.completion;
        s["m"] = e.message;
    }
    std::fputs(Journal::line_of(s, {{"serial", e.serial}}).c_str(), stdout);
}

int main(int argc, char** argv) {
    if (argc < 3) return 2;
    std::string mode = argv[1], dir = argv[2];
    JournalRecovered rec;
    auto log = [](const std::string& text) { std::printf("log %s\n", text.c_str()); };
    auto j = Journal::open(dir, "Restarter", 1, mode == "read" && argc > 3 ? std::stoul(argv[3]) : 64, log, rec);
    if (!j) return 1;
    if (mode == "read") {
        std::fputs(Journal::line_of({{"k", "r"}}, {{"crashed", rec.crashed ? 1 : 0}, {"serial", rec.last_serial}})
                       .c_str(), stdout);
        for (const auto& e : rec.unfinished) print(e);
        for (const auto& e : rec.finished) print(e);
        std::fflush(stdout);
        _exit(0);
    }
    j->start(200);
    j->note(JournalEntry{"cpp-1", "Ground", "Restarter", 7, 'q', "", ""});
    j->note(JournalEntry{"cpp-2", "Ground", "Restarter", 7, 'q', "", ""});
    j->note(JournalEntry{"cpp-2", "Ground", "Restarter", 7, 'x', "", ""});
    j->note(JournalEntry{"cpp-3", "Ground", "Restarter", 7, 'x', "", ""});
    j->note(JournalEntry{"cpp-3", "Ground", "Restarter", 7, 'c', "ACK_COMPLETED_OK", "done \"\xc3\xa9\xe2\x98\x83\""});
    j->serial(205);
    if (!j->sync()) return 1;
    std::fflush(stdout);
    _exit(0);  // a crash: no stop record
}
