// The restart journal (journal.hpp): the Python runtime's format, written and read here.
#include "rapid_runtime/journal.hpp"

#include <fcntl.h>
#include <pwd.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fstream>
#include <sstream>

namespace rapid_runtime {
namespace {

constexpr std::size_t kCompactFactor = 4;
constexpr std::size_t kMaxRead = 64u * 1024u * 1024u;

std::uint32_t crc32(const std::string& data) {
    static std::uint32_t table[256];
    static bool ready = false;
    if (!ready) {  // the zlib polynomial, reflected
        for (std::uint32_t i = 0; i < 256; ++i) {
            std::uint32_t c = i;
            for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
            table[i] = c;
        }
        ready = true;
    }
    std::uint32_t c = 0xFFFFFFFFu;
    for (unsigned char b : data) c = table[(c ^ b) & 0xFF] ^ (c >> 8);
    return c ^ 0xFFFFFFFFu;
}

// JSON string as Python's json.dumps(ensure_ascii=True) writes it: ASCII only, \uXXXX for
// the rest (UTF-16 surrogate pairs past U+FFFF); invalid UTF-8 bytes become U+FFFD.
std::string quote(const std::string& s) {
    std::string out = "\"";
    char buf[16];
    for (std::size_t i = 0; i < s.size();) {
        unsigned char c = static_cast<unsigned char>(s[i]);
        std::uint32_t cp = 0xFFFD;
        std::size_t n = 1;
        if (c < 0x80) {
            cp = c;
        } else if ((c & 0xE0) == 0xC0 && i + 1 < s.size()) {
            cp = ((c & 0x1Fu) << 6) | (static_cast<unsigned char>(s[i + 1]) & 0x3Fu);
            n = 2;
        } else if ((c & 0xF0) == 0xE0 && i + 2 < s.size()) {
            cp = ((c & 0x0Fu) << 12) | ((static_cast<unsigned char>(s[i + 1]) & 0x3Fu) << 6) |
                 (static_cast<unsigned char>(s[i + 2]) & 0x3Fu);
            n = 3;
        } else if ((c & 0xF8) == 0xF0 && i + 3 < s.size()) {
            cp = ((c & 0x07u) << 18) | ((static_cast<unsigned char>(s[i + 1]) & 0x3Fu) << 12) |
                 ((static_cast<unsigned char>(s[i + 2]) & 0x3Fu) << 6) | (static_cast<unsigned char>(s[i + 3]) & 0x3Fu);
            n = 4;
        }
        i += n;
        if (cp == '"') out += "\\\"";
        else if (cp == '\\') out += "\\\\";
        else if (cp == '\n') out += "\\n";
        else if (cp == '\r') out += "\\r";
        else if (cp == '\t') out += "\\t";
        else if (cp >= 0x20 && cp < 0x7F) out += static_cast<char>(cp);
        else if (cp < 0x10000) {
            std::snprintf(buf, sizeof buf, "\\u%04x", static_cast<unsigned>(cp));
            out += buf;
        } else {
            cp -= 0x10000;
            std::snprintf(buf, sizeof buf, "\\u%04x\\u%04x", static_cast<unsigned>(0xD800 + (cp >> 10)),
                          static_cast<unsigned>(0xDC00 + (cp & 0x3FF)));
            out += buf;
        }
    }
    return out + "\"";
}

void put_utf8(std::string& out, std::uint32_t cp) {
    if (cp < 0x80) out += static_cast<char>(cp);
    else if (cp < 0x800) { out += static_cast<char>(0xC0 | (cp >> 6)); out += static_cast<char>(0x80 | (cp & 0x3F)); }
    else if (cp < 0x10000) {
        out += static_cast<char>(0xE0 | (cp >> 12));
        out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
        out += static_cast<char>(0x80 | (cp & 0x3F));
    } else {
        out += static_cast<char>(0xF0 | (cp >> 18));
        out += static_cast<char>(0x80 | ((cp >> 12) & 0x3F));
        out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
        out += static_cast<char>(0x80 | (cp & 0x3F));
    }
}

// A flat JSON object of strings and integers (what the journal writes); false otherwise.
class Flat {
public:
    explicit Flat(const std::string& t) : t_(t) {}
    bool parse(std::map<std::string, std::string>& strings, std::map<std::string, std::int64_t>& numbers) {
        space();
        if (!eat('{')) return false;
        space();
        if (eat('}')) return end();
        for (;;) {
            std::string key;
            space();
            if (!string(key)) return false;
            space();
            if (!eat(':')) return false;
            space();
            if (i_ < t_.size() && t_[i_] == '"') {
                std::string v;
                if (!string(v)) return false;
                strings[key] = v;
            } else {
                std::int64_t v = 0;
                if (!number(v)) return false;
                numbers[key] = v;
            }
            space();
            if (eat(',')) continue;
            if (eat('}')) return end();
            return false;
        }
    }

private:
    bool end() { space(); return i_ == t_.size(); }
    void space() { while (i_ < t_.size() && (t_[i_] == ' ' || t_[i_] == '\t')) ++i_; }
    bool eat(char c) { if (i_ < t_.size() && t_[i_] == c) { ++i_; return true; } return false; }
    bool hex4(std::uint32_t& v) {
        if (i_ + 4 > t_.size()) return false;
        v = 0;
        for (int k = 0; k < 4; ++k) {
            char c = t_[i_++];
            v <<= 4;
            if (c >= '0' && c <= '9') v |= static_cast<std::uint32_t>(c - '0');
            else if (c >= 'a' && c <= 'f') v |= static_cast<std::uint32_t>(c - 'a' + 10);
            else if (c >= 'A' && c <= 'F') v |= static_cast<std::uint32_t>(c - 'A' + 10);
            else return false;
        }
        return true;
    }
    bool string(std::string& out) {
        if (!eat('"')) return false;
        while (i_ < t_.size()) {
            char c = t_[i_++];
            if (c == '"') return true;
            if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x80) return false;  // (a line is ASCII)
            if (c != '\\') { out += c; continue; }
            if (i_ >= t_.size()) return false;
            char e = t_[i_++];
            switch (e) {
                case '"': out += '"'; break;
                case '\\': out += '\\'; break;
                case '/': out += '/'; break;
                case 'b': out += '\b'; break;
                case 'f': out += '\f'; break;
                case 'n': out += '\n'; break;
                case 'r': out += '\r'; break;
                case 't': out += '\t'; break;
                case 'u': {
                    std::uint32_t cp = 0;
                    if (!hex4(cp)) return false;
                    if (cp >= 0xD800 && cp < 0xDC00 && i_ + 1 < t_.size() && t_[i_] == '\\' && t_[i_ + 1] == 'u') {
                        std::size_t back = i_;
                        i_ += 2;
                        std::uint32_t lo = 0;
                        if (hex4(lo) && lo >= 0xDC00 && lo < 0xE000) cp = 0x10000 + ((cp - 0xD800) << 10) + (lo - 0xDC00);
                        else i_ = back;
                    }
                    if (cp >= 0xD800 && cp < 0xE000) cp = 0xFFFD;  // a lone surrogate: not UTF-8
                    put_utf8(out, cp);
                    break;
                }
                default: return false;
            }
        }
        return false;
    }
    bool number(std::int64_t& v) {
        std::size_t start = i_;
        if (eat('-')) {}
        while (i_ < t_.size() && t_[i_] >= '0' && t_[i_] <= '9') ++i_;
        if (i_ == start || (i_ == start + 1 && t_[start] == '-') || i_ - start > 19) return false;
        try { v = std::stoll(t_.substr(start, i_ - start)); } catch (...) { return false; }
        return true;
    }
    const std::string& t_;
    std::size_t i_ = 0;
};

std::string record_of(const JournalEntry& e) {
    std::map<std::string, std::string> s{{"k", std::string(1, e.state)}, {"id", e.cmd_id}, {"src", e.src_name},
                                         {"asset", e.asset_name}};
    if (e.state == 'c') {
        s["c"] = e.completion;
        s["m"] = e.message;
    }
    return Journal::line_of(s, {{"serial", e.serial}});
}

void fsync_dir(const std::string& path) {
    std::string dir = path.substr(0, path.find_last_of('/') == std::string::npos ? 0 : path.find_last_of('/'));
    int d = ::open(dir.empty() ? "." : dir.c_str(), O_RDONLY);
    if (d >= 0) { ::fsync(d); ::close(d); }
}

bool make_dirs(const std::string& folder) {
    std::string part;
    std::stringstream ss(folder);
    std::string piece;
    if (!folder.empty() && folder[0] == '/') part = "/";
    while (std::getline(ss, piece, '/')) {
        if (piece.empty()) continue;
        part += piece + "/";
        if (::mkdir(part.c_str(), 0755) != 0 && errno != EEXIST) return false;
    }
    return true;
}

}  // namespace

std::int64_t restart_serial(std::int64_t requested, const JournalRecovered& recovered, std::int64_t now) {
    if (requested >= 0 || recovered.last_serial <= 0) return requested;
    return std::max(now, recovered.last_serial + 1);
}

std::string Journal::default_dir() {
    const char* state = std::getenv("RAPID_STATE_DIR");
    if (state != nullptr && *state) return state;
    const char* xdg = std::getenv("XDG_STATE_HOME");
    if (xdg != nullptr && *xdg) return std::string(xdg) + "/rapid_runtime";
    const char* home = std::getenv("HOME");
    std::string base;
    if (home != nullptr && *home) {
        base = home;
    } else if (const passwd* pw = ::getpwuid(::getuid())) {  // as Python's expanduser("~")
        base = pw->pw_dir;
    }
    return base + "/.local/state/rapid_runtime";
}

std::string Journal::file_name(const std::string& asset, int domain) {
    std::string name;
    for (char c : asset.substr(0, 64))
        name += (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.' || c == '-') ? c : '_';
    return name + "-domain" + std::to_string(domain) + ".journal";
}

std::string Journal::line_of(const std::map<std::string, std::string>& strings,
                             const std::map<std::string, std::int64_t>& numbers) {
    std::string json = "{";
    auto k = strings.find("k");  // "k" first, as the Python runtime writes it (not required)
    if (k != strings.end()) json += "\"k\":" + quote(k->second);
    for (const auto& [key, v] : strings)
        if (key != "k") json += (json.size() > 1 ? "," : "") + quote(key) + ":" + quote(v);
    for (const auto& [key, v] : numbers) json += (json.size() > 1 ? "," : "") + quote(key) + ":" + std::to_string(v);
    json += "}";
    char crc[16];
    std::snprintf(crc, sizeof crc, "%08x", static_cast<unsigned>(crc32(json)));
    return std::string(crc) + " " + json + "\n";
}

bool Journal::parse_line(const std::string& raw, std::map<std::string, std::string>& strings,
                         std::map<std::string, std::int64_t>& numbers) {
    if (raw.size() < 11 || raw.back() != '\n' || raw[8] != ' ') return false;
    std::string body = raw.substr(9, raw.size() - 10);
    char* endp = nullptr;
    std::string head = raw.substr(0, 8);
    unsigned long want = std::strtoul(head.c_str(), &endp, 16);
    if (endp != head.c_str() + 8 || want != crc32(body)) return false;
    if (!Flat(body).parse(strings, numbers)) return false;
    auto k = strings.find("k");
    if (k == strings.end()) return false;
    const std::string& kind = k->second;
    if (kind == "q" || kind == "x" || kind == "c") {
        for (const char* f : {"id", "src", "asset"})
            if (!strings.count(f)) return false;
        if (!numbers.count("serial")) return false;
        if (kind == "c" && (!strings.count("c") || !strings.count("m"))) return false;
        return true;
    }
    if (kind == "s") return numbers.count("serial") == 1;
    return kind == "start" || kind == "stop";
}

Journal::Journal(std::string path, int fd, std::size_t window, Log log)
    : path_(std::move(path)), fd_(fd), window_(window), log_(std::move(log)) {}

Journal::~Journal() {
    if (fd_ >= 0) ::close(fd_);
}

std::unique_ptr<Journal> Journal::open(const std::string& folder, const std::string& asset, int domain,
                                       std::size_t window, Log log, JournalRecovered& recovered) {
    std::string path = folder + "/" + file_name(asset, domain);
    if (!make_dirs(folder)) {
        log("journal " + path + ": cannot be opened (" + std::strerror(errno) + "); running without one");
        return nullptr;
    }
    int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_APPEND | O_CLOEXEC, 0600);
    if (fd < 0) {
        log("journal " + path + ": cannot be opened (" + std::strerror(errno) + "); running without one");
        return nullptr;
    }
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
        ::close(fd);
        log("journal " + path + ": in use by another bridge of this asset and domain; running without one");
        return nullptr;
    }
    std::unique_ptr<Journal> j(new Journal(path, fd, window, std::move(log)));
    j->recover(recovered);
    if (j->fd_ < 0) return nullptr;  // said in the log
    return j;
}

void Journal::recover(JournalRecovered& out) {
    std::string raw;
    {
        std::ifstream in(path_, std::ios::binary);
        raw.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
    std::size_t bad = 0, first_bad = 0, n = 0, sound = 0;
    bool last_stop = false;
    if (raw.size() > kMaxRead) {
        raw.clear();
        bad = first_bad = 1;
    }
    for (std::size_t pos = 0; pos < raw.size();) {
        std::size_t nl = raw.find('\n', pos);
        std::string line = raw.substr(pos, nl == std::string::npos ? std::string::npos : nl - pos + 1);
        pos = nl == std::string::npos ? raw.size() : nl + 1;
        ++n;
        std::map<std::string, std::string> s;
        std::map<std::string, std::int64_t> num;
        if (!parse_line(line, s, num)) {
            ++bad;
            if (!first_bad) first_bad = n;
            continue;
        }
        ++sound;
        const std::string& k = s["k"];
        last_stop = k == "stop";
        if (num.count("serial") && (k == "s" || k == "start")) last_serial_ = std::max(last_serial_, num["serial"]);
        if (k == "q" || k == "x" || k == "c")
            apply(JournalEntry{s["id"], s["src"], s["asset"], num["serial"], k[0], s["c"], s["m"]});
    }
    out.last_serial = last_serial_;
    bool crashed = sound > 0 && !last_stop;
    if (bad) {
        char stamp[32];
        std::time_t now = std::time(nullptr);
        std::strftime(stamp, sizeof stamp, "%Y%m%dT%H%M%S", std::localtime(&now));
        std::string aside = path_ + ".damaged-" + stamp + "-" + std::to_string(::getpid());
        if (::rename(path_.c_str(), aside.c_str()) != 0) {
            log_("journal " + path_ + ": damaged and cannot be set aside (" + std::strerror(errno) +
                 "); running without one");
            ::close(fd_);
            fd_ = -1;
            return;
        }
        log_("journal " + path_ + ": " + std::to_string(bad) + " damaged line(s) (first: line " +
             std::to_string(first_bad) + "), set aside as " + aside.substr(aside.find_last_of('/') + 1) + "; " +
             std::to_string(sound) + " sound record(s) kept");
        crashed = true;
    }
    if (crashed) {
        out.crashed = true;
        out.unfinished = live_;
        out.finished.assign(done_.begin(), done_.end());
    } else {
        live_.clear();
        done_.clear();
    }
    rewrite();
}

void Journal::apply(const JournalEntry& e) {
    auto same = [&](const JournalEntry& o) { return o.cmd_id == e.cmd_id; };
    if (e.state == 'c') {
        live_.erase(std::remove_if(live_.begin(), live_.end(), same), live_.end());
        done_.erase(std::remove_if(done_.begin(), done_.end(), same), done_.end());
        done_.push_back(e);
        while (done_.size() > window_) done_.pop_front();
        return;
    }
    auto it = std::find_if(live_.begin(), live_.end(), same);
    if (it != live_.end()) *it = e;
    else live_.push_back(e);
}

std::size_t Journal::lines() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return lines_;
}

std::size_t Journal::syncs() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return syncs_;
}

bool Journal::unsynced() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return unsynced_;
}

void Journal::failed(const std::string& what) {
    if (failing_) return;
    failing_ = true;
    log_("journal " + path_ + ": " + what + " (" + std::strerror(errno) +
         "): a crash now would leave commands without an outcome");
}

void Journal::start(std::int64_t serial) {
    std::lock_guard<std::mutex> lock(mutex_);
    append(line_of({{"k", "start"}}, {{"serial", serial}, {"t", static_cast<std::int64_t>(std::time(nullptr))}}));
    last_serial_ = std::max(last_serial_, serial);
}

void Journal::serial(std::int64_t serial) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (serial <= last_serial_) return;
    last_serial_ = serial;
    append(line_of({{"k", "s"}}, {{"serial", serial}}));
}

void Journal::note(const JournalEntry& entry) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (entry.state != 'c') {
        auto it = std::find_if(live_.begin(), live_.end(), [&](const JournalEntry& o) { return o.cmd_id == entry.cmd_id; });
        if (it != live_.end() && (it->state == entry.state || it->state == 'x')) return;  // progress, requeue
    }
    apply(entry);
    append(record_of(entry));
}

bool Journal::sync() {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!unsynced_ || fd_ < 0) return true;
    if (::fdatasync(fd_) != 0) {
        failed("not synced");
        return false;
    }
    failing_ = false;
    unsynced_ = false;
    ++syncs_;
    if (lines_ > kCompactFactor * window_ + live_.size() + 16) rewrite();
    return true;
}

void Journal::close(bool clean) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (fd_ < 0) return;
    if (clean) append(line_of({{"k", "stop"}}, {}));
    ::fdatasync(fd_);
    ::close(fd_);
    fd_ = -1;
}

void Journal::append(const std::string& line) {
    if (fd_ < 0) return;
    // O_APPEND: a kill -9 loses nothing written; a power cut, what was not synced
    if (::write(fd_, line.data(), line.size()) != static_cast<ssize_t>(line.size())) failed("a record not written");
    ++lines_;
    unsynced_ = true;
}

void Journal::rewrite() {
    // compaction: the serial, the last `window` outcomes and the live commands in a new file,
    // fsynced, renamed over the journal, the folder fsynced; the lock moves to the new file
    std::string data;
    std::size_t count = 0;
    if (last_serial_) { data += line_of({{"k", "s"}}, {{"serial", last_serial_}}); ++count; }
    for (const auto& e : done_) { data += record_of(e); ++count; }
    for (const auto& e : live_) { data += record_of(e); ++count; }
    std::string tmp = path_ + ".new";
    int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_APPEND | O_CLOEXEC, 0600);
    if (fd < 0 || ::flock(fd, LOCK_EX | LOCK_NB) != 0 ||
        (!data.empty() && ::write(fd, data.data(), data.size()) != static_cast<ssize_t>(data.size())) ||
        ::fsync(fd) != 0 || ::rename(tmp.c_str(), path_.c_str()) != 0) {
        log_(std::string("journal ") + path_ + ": not compacted (" + std::strerror(errno) + ")");
        if (fd >= 0) ::close(fd);
        return;
    }
    fsync_dir(path_);
    if (fd_ >= 0) ::close(fd_);
    fd_ = fd;
    lines_ = count;
    unsynced_ = false;
}

}  // namespace rapid_runtime
