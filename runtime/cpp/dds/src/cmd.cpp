#include "rapid_runtime/dds/cmd.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <rapid_runtime/text.hpp>

#include "rapid_runtime/dds/client.hpp"

namespace rapid_runtime {
namespace dds {

namespace {

using Clock = std::chrono::steady_clock;

struct Args {
    std::string asset, partition, transport = "local", qos, source = "rapid_cmd", target, id;
    std::optional<int> domain;
    QueueAction action = QueueAction::Bypass;
    double timeout = 30, discover = 2, rtt = 0;
    bool no_check = false, no_wait = false;
    long long repeat = 0, flood = 0, window = 0;
    std::vector<std::string> words;  // SUBSYSTEM COMMAND key=value...
};

void usage(std::ostream& out, const char* prog) {
    out << "usage: " << prog
        << " [options] SUBSYSTEM COMMAND [key=value ...]\n\n"
           "Send a command to a live RAPID asset, arguments by name, checked against its dictionary;\n"
           "print its acks. Exit 0 on COMPLETED/OK, else 1 (2: usage).\n"
           "  --asset NAME        the asset (default: the built-in tables')\n"
           "  --partition P       its DDS partition (default: its own name)\n"
           "  --domain N          DDS domain (default: the asset's)\n"
           "  --transport NAME    participant profile rapid_NAME: local (loopback only, default), lan, wan\n"
           "  --qos FILE          the asset's generated qos/fastdds/rapid_qos_profiles.xml\n"
           "  --source NAME       cmdSrc and srcName (default rapid_cmd)\n"
           "  --action A          BYPASS (default), APPEND, INSERT, REPLACE, DELETE\n"
           "  --target CMDID      the queued command INSERT, REPLACE or DELETE acts on\n"
           "  --id CMDID          this command's cmdId (default: a fresh one)\n"
           "  --timeout S         seconds to wait for the asset, then for completion (default 30)\n"
           "  --discover S        seconds to wait for the live CommandConfig (default 2)\n"
           "  --rtt S             the link's round trip (0..600): the waits grow by 2 of them for\n"
           "                      an answer, 6 for finding the asset and its CommandConfig\n"
           "  --no-check          send values outside their range or allowed values\n"
           "  --no-wait           return after the first ack\n"
           "  --repeat N          benchmark: N commands one after the other; JSON latency figures\n"
           "  --flood N           benchmark: N commands at once (--window W in flight); JSON counts\n";
}

// As `rapidgen cmd --rtt` (rapidgen/cmd/timing.py): a loopback wait over a link grows by
// what the link costs: an answer a round trip, a lost packet's repair another; a late
// joiner's first durable sample (participants, endpoints, request, history, one loss) 6.
constexpr double ANSWER_TRIPS = 2, DISCOVERY_TRIPS = 6, MAX_RTT = 600;

double allow(double seconds, double rtt, double trips = ANSWER_TRIPS) { return seconds + trips * rtt; }

bool to_number(const std::string& text, double& out) {
    char* end = nullptr;
    out = std::strtod(text.c_str(), &end);
    return !text.empty() && end != nullptr && *end == '\0' && std::isfinite(out);
}

bool to_integer(const std::string& text, long long& out) {
    char* end = nullptr;
    out = std::strtoll(text.c_str(), &end, 10);
    return !text.empty() && end != nullptr && *end == '\0';
}

std::optional<QueueAction> action_of(std::string text) {
    for (auto& c : text) c = static_cast<char>(c >= 'a' && c <= 'z' ? c - 'a' + 'A' : c);
    if (text.rfind("QUEUE_", 0) == 0) text = text.substr(6);
    for (auto a : {QueueAction::Bypass, QueueAction::Append, QueueAction::Insert, QueueAction::Replace,
                   QueueAction::Delete})
        if (name_of(a).substr(6) == text) return a;
    return std::nullopt;
}

// false: a usage error, said on stderr
bool parse(int argc, char** argv, Args& a, bool& help) {
    for (int i = 1; i < argc; ++i) {
        std::string key = argv[i];
        if (key == "--help" || key == "-h") {
            help = true;
            return true;
        }
        if (key == "--no-check" || key == "--no-wait") {
            (key == "--no-check" ? a.no_check : a.no_wait) = true;
            continue;
        }
        if (key.rfind("--", 0) != 0) {
            a.words.push_back(key);
            continue;
        }
        if (i + 1 >= argc) {
            std::cerr << argv[0] << ": " << visible(key) << " needs a value\n";
            return false;
        }
        std::string value = argv[++i];
        double x = 0;
        long long n = 0;
        bool ok = true;
        if (key == "--asset") a.asset = value, ok = !value.empty();
        else if (key == "--partition") a.partition = value, ok = !value.empty();
        else if (key == "--transport") a.transport = value, ok = !value.empty();
        else if (key == "--qos") a.qos = value, ok = !value.empty();
        else if (key == "--source") a.source = value, ok = !value.empty();
        else if (key == "--target") a.target = value;
        else if (key == "--id") a.id = value, ok = !value.empty();
        else if (key == "--domain") ok = to_integer(value, n) && n >= 0 && n <= 232, a.domain = static_cast<int>(n);
        else if (key == "--timeout") ok = to_number(value, x) && x > 0, a.timeout = x;
        else if (key == "--discover") ok = to_number(value, x) && x >= 0, a.discover = x;
        else if (key == "--rtt") ok = to_number(value, x) && x >= 0 && x <= MAX_RTT, a.rtt = x;
        else if (key == "--repeat") ok = to_integer(value, n) && n > 0, a.repeat = n;
        else if (key == "--flood") ok = to_integer(value, n) && n > 0, a.flood = n;
        else if (key == "--window") ok = to_integer(value, n) && n > 0, a.window = n;
        else if (key == "--action") {
            auto act = action_of(value);
            ok = act.has_value();
            if (ok) a.action = *act;
        } else {
            std::cerr << argv[0] << ": unknown option " << visible(key) << "\n";
            return false;
        }
        if (!ok) {
            std::cerr << argv[0] << ": bad value for " << key << ": " << visible(value) << "\n";
            return false;
        }
    }
    if (a.words.size() < 2) {
        std::cerr << argv[0] << ": SUBSYSTEM and COMMAND are needed\n";
        return false;
    }
    return true;
}

std::string shown(const Value& v) {
    char buf[32];
    auto num = [&](double x) {
        std::snprintf(buf, sizeof buf, "%g", x);
        return std::string(buf);
    };
    if (auto* b = std::get_if<bool>(&v)) return *b ? "true" : "false";
    if (auto* s = std::get_if<std::string>(&v)) return "'" + visible(*s, 64) + "'";
    if (auto* d = std::get_if<Vec3d>(&v)) return num((*d)[0]) + "," + num((*d)[1]) + "," + num((*d)[2]);
    if (auto* m = std::get_if<Mat33f>(&v)) {
        std::string out;
        for (float f : *m) out += (out.empty() ? "" : ",") + num(f);
        return out;
    }
    return repr(v);
}

// Sending a command again with the same cmdId, as `rapidgen cmd` does (rapidgen/cmd/recover.py,
// docs/runtime.md "The ground's part"), at most MAX_RESENDS times; safe, since a RAPID asset
// drops a repeated cmdId (its journal's too) and answers it from its ack history:
// - the asset came back (a new participant with a command reader and an ack writer) and
//   has not answered SETTLE s + 2 round trips later: the command was lost in the old one;
// - no ack at all UNANSWERED s + 2 round trips after the send, while the asset is there:
//   the writer matched the asset's reader before that reader knew the writer, and a
//   volatile reader need not deliver what was written before it matched (seen across the
//   lunar link). A RAPID asset answers a command at once.
constexpr double SETTLE = 3, UNANSWERED = 5;
constexpr int MAX_RESENDS = 3;

struct Resend {
    Resend(Client& c, Cmd command, double rtt)
        : client(c), cmd(std::move(command)), settle(allow(SETTLE, rtt)), unanswered(allow(UNANSWERED, rtt)),
          known(c.asset_participants()) {}

    Client& client;
    Cmd cmd;  // as sent, cmd_id filled
    double settle, unanswered;
    std::set<std::string> known;  // the asset's participants so far
    std::optional<Clock::time_point> back_at;  // when a new one appeared
    Clock::time_point sent = Clock::now();
    int done = 0;

    // True when it was sent again now (call while the command has no final ack).
    bool due(bool answered) {
        if (done >= MAX_RESENDS) return false;
        const auto now = Clock::now();
        const auto current = client.asset_participants();
        for (const auto& p : current)
            if (known.insert(p).second) back_at = now;  // a later newcomer restarts the wait
        auto since = [&](Clock::time_point t) { return std::chrono::duration<double>(now - t).count(); };
        std::string why;
        if (back_at && since(*back_at) >= settle) {
            why = "came back (a new participant) and has not answered within " + seconds(settle) +
                  " s: the command was lost in the old one";
        } else if (!back_at && !answered && since(sent) >= unanswered && !current.empty()) {
            why = "has not answered within " + seconds(unanswered) + " s: the command did not reach it";
        } else {
            return false;
        }
        back_at.reset();
        sent = now;
        ++done;
        client.send_raw(cmd);
        std::cerr << "rapid_cmd: " << visible(client.asset()) << " " << why
                  << "; sending it again with the same cmdId (" << done << " of " << MAX_RESENDS << ")" << std::endl;
        return true;
    }

    static std::string seconds(double s) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%g", s);
        return buf;
    }
};

// cmd_id's acks as they come (printed when `print`) until the final one (or the first,
// or the deadline; a resend starts the wait over).
std::vector<AckEvent> follow(Client& client, const std::string& cmd_id, double seconds, bool first_only,
                             Resend* resend = nullptr, bool print = true) {
    auto end = Clock::now() + std::chrono::duration<double>(seconds);
    std::size_t printed = 0;
    while (true) {
        double left = std::chrono::duration<double>(end - Clock::now()).count();
        double slice = resend != nullptr ? std::min(left, 0.25) : left;
        // (not printing: woken once, by the final ack, not once per ack as they come)
        auto acks = print || first_only ? client.wait_count(cmd_id, printed + 1, std::max(0.0, slice))
                                        : client.wait_final(cmd_id, std::max(0.0, slice));
        for (; printed < acks.size(); ++printed)
            if (print) std::cout << "  " << describe(acks[printed]) << std::endl;
        bool final = std::any_of(acks.begin(), acks.end(), [](const AckEvent& e) { return e.final(); });
        if (!acks.empty() && (first_only || final)) return acks;
        if (resend != nullptr && resend->due(!acks.empty()))
            end = std::max(end, Clock::now() + std::chrono::duration<double>(seconds));
        else if (left <= 0)
            return acks;
    }
}

double percentile(std::vector<double> v, double q) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    auto i = static_cast<std::size_t>(std::ceil(q * static_cast<double>(v.size()))) ;
    return v[std::min(v.size() - 1, i == 0 ? 0 : i - 1)];
}

int repeat(Client& client, const Args& a, const SendOptions& how) {
    std::vector<double> us;
    us.reserve(static_cast<std::size_t>(a.repeat));
    long long failed = 0;
    const auto start = Clock::now();
    for (long long i = 0; i < a.repeat; ++i) {
        auto t0 = Clock::now();
        Resend again(client, client.prepare_text(a.words[0], a.words[1], {a.words.begin() + 2, a.words.end()}, how),
                     a.rtt);
        auto id = client.send_raw(again.cmd);
        again.cmd.cmd_id = id;
        auto acks = follow(client, id, allow(a.timeout, a.rtt), false, &again, false);
        auto t1 = Clock::now();
        client.forget(id);
        if (acks.empty() || !acks.back().final()) {
            ++failed;
            continue;
        }
        us.push_back(std::chrono::duration<double, std::micro>(t1 - t0).count());
    }
    double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    std::printf("{\"count\": %lld, \"answered\": %zu, \"p50_us\": %.1f, \"p99_us\": %.1f, \"max_us\": %.1f, "
                "\"per_s\": %.1f}\n",
                a.repeat, us.size(), percentile(us, 0.5), percentile(us, 0.99), percentile(us, 1.0),
                static_cast<double>(us.size()) / seconds);
    return failed == 0 ? 0 : 1;
}

int flood(Client& client, const Args& a, const SendOptions& how) {
    const std::size_t total = static_cast<std::size_t>(a.flood);
    const std::size_t window = a.window > 0 ? static_cast<std::size_t>(a.window) : total;
    std::vector<std::string> inflight;
    std::size_t sent = 0, finals = 0, ok = 0;
    const auto start = Clock::now();
    auto drain = [&](std::size_t keep, double seconds) {
        // waits for the oldest in flight until at most `keep` remain (or the deadline)
        const auto end = Clock::now() + std::chrono::duration<double>(seconds);
        while (inflight.size() > keep) {
            double left = std::chrono::duration<double>(end - Clock::now()).count();
            auto acks = client.wait_final(inflight.front(), std::max(0.0, left));
            if (acks.empty() || !acks.back().final()) return false;
            ++finals;
            ok += acks.back().ok();
            client.forget(inflight.front());
            inflight.erase(inflight.begin());
        }
        return true;
    };
    bool lost = false;
    while (sent < total && !lost) {
        inflight.push_back(client.send_text(a.words[0], a.words[1], {a.words.begin() + 2, a.words.end()}, how));
        ++sent;
        if (inflight.size() >= window) lost = !drain(window - 1, allow(a.timeout, a.rtt));
    }
    if (!lost) drain(0, allow(a.timeout, a.rtt));
    double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    std::printf("{\"sent\": %zu, \"final\": %zu, \"ok\": %zu, \"lost\": %zu, \"seconds\": %.3f, \"per_s\": %.1f}\n",
                sent, finals, ok, total - finals, seconds, static_cast<double>(finals) / seconds);
    return finals == total ? 0 : 1;
}

}  // namespace

int run_cmd(int argc, char** argv, const CmdProgram& program) {
    const char* prog = argc > 0 ? argv[0] : "rapid_cmd";
    Args a;
    bool help = false;
    if (!parse(argc, argv, a, help)) {
        usage(std::cerr, prog);
        return 2;
    }
    if (help) {
        usage(std::cout, prog);
        return 0;
    }
    ClientOptions o;
    o.asset = a.asset;
    o.partition = a.partition;
    o.source = a.source;
    o.domain = a.domain.value_or(-1);
    o.transport = a.transport;
    if (!a.qos.empty()) o.profiles_file = a.qos;
    else o.profiles_xml = std::string(program.profiles_xml);
    const Tables* tables = program.tables;
    if (tables != nullptr && !a.asset.empty() && a.asset != tables->name) tables = nullptr;  // another asset
    SendOptions how;
    how.action = a.action;
    how.target = a.target;
    how.cmd_id = a.id;
    how.limits = !a.no_check;
    try {
        Client client(o, tables);
        const double discover = allow(a.discover, a.rtt, DISCOVERY_TRIPS);
        const double find = allow(a.timeout, a.rtt, DISCOVERY_TRIPS), answer = allow(a.timeout, a.rtt);
        if (a.discover > 0 && !client.read_dictionary(discover)) {
            std::cerr << "rapid_cmd: no CommandConfig from " << visible(client.asset()) << " within " << discover
                      << " s (domain " << client.domain() << ")"
                      << (tables != nullptr ? "; using the built-in tables" : "") << std::endl;
        }
        if (client.dictionary() == nullptr) {
            std::cerr << "rapid_cmd: no command dictionary for " << visible(client.asset())
                      << ": the asset publishes none (is it running? --domain, --transport)" << std::endl;
            return 1;
        }
        const std::vector<std::string> words(a.words.begin() + 2, a.words.end());
        Cmd cmd = client.prepare_text(a.words[0], a.words[1], words, how);  // checked before waiting
        if (!client.wait_for_asset(find)) {
            std::cerr << "rapid_cmd: no asset " << visible(client.asset()) << " reads commands on domain "
                      << client.domain() << ", partition '" << visible(client.partition()) << "' (waited "
                      << find << " s)" << std::endl;
            return 1;
        }
        if (a.repeat > 0) return repeat(client, a, how);
        if (a.flood > 0) return flood(client, a, how);
        if (!a.target.empty()) client.follow(a.target);
        Resend again(client, std::move(cmd), a.rtt);  // the command is kept there, as sent
        auto id = client.send_raw(again.cmd);
        again.cmd.cmd_id = id;
        const std::vector<Value>& values = again.cmd.args;
        std::string line = visible(client.asset()) + " <- " + visible(a.words[0]) + "/" + visible(a.words[1]);
        // the values as sent (defaults included), by name
        const auto* spec = client.dictionary()->command(a.words[0], a.words[1]).spec;
        for (std::size_t i = 0; i < values.size(); ++i) line += " " + spec->params[i].name + "=" + shown(values[i]);
        line += "  [cmdId " + visible(id) + ", " + std::string(name_of(a.action)) +
                (a.target.empty() ? "" : " " + visible(a.target)) + ", from " + visible(a.source) + "]";
        std::cout << line << std::endl;
        auto acks = follow(client, id, answer, a.no_wait, &again);
        if (acks.empty()) {
            std::cout << "  no ack within " << answer << " s" << std::endl;
            return 1;
        }
        const AckEvent& last = acks.back();
        if (a.action == QueueAction::Delete && last.final()) {
            std::cout << "target " << visible(a.target) << ":" << std::endl;
            follow(client, a.target, allow(3.0, a.rtt), false);
        }
        if (a.no_wait) return !last.final() || last.ok() ? 0 : 1;
        return last.ok() ? 0 : 1;
    } catch (const CommandError& e) {
        std::cerr << "rapid_cmd: error: " << e.what() << std::endl;
        return 1;
    } catch (const std::exception& e) {
        std::cerr << prog << ": " << e.what() << std::endl;
        return 1;
    }
}

}  // namespace dds
}  // namespace rapid_runtime
