#include "rapid_runtime/dds/program.hpp"

#include <atomic>
#include <cctype>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <iostream>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <rapid_runtime/journal.hpp>
#include <rapid_runtime/simulator.hpp>
#include <rapid_runtime/text.hpp>

namespace rapid_runtime {
namespace dds {

namespace {

std::atomic<bool> signalled{false};

extern "C" void on_signal(int) { signalled = true; }

struct Args {
    bool simulate = false;
    double sim_speed = 1.0;
    std::optional<int> domain;
    std::string transport = "local";
    std::string qos;
    double seconds = -1;
    std::size_t command_window = COMMAND_WINDOW;
    std::string journal;  // --journal DIR (default: Journal::default_dir())
    bool no_journal = false;
    std::vector<std::string> breaks;  // --break KIND: test builds only (breaks.hpp)
    int stop_timeout_ms = DEFAULT_STOP_TIMEOUT_MS;
    int shutdown_timeout_ms = DEFAULT_SHUTDOWN_TIMEOUT_MS;
};

void usage(std::ostream& out, const char* prog, const Tables& t) {
    out << "usage: " << prog
        << " [--simulate] [--sim-speed X] [--domain N] [--transport local|lan|wan] [--qos PROFILES_XML]\n"
           "       [--seconds S] [--command-window N] [--journal DIR | --no-journal]\n"
           "       [--stop-timeout MS] [--shutdown-timeout MS]\n\n"
           "RAPID bridge of asset "
        << visible(t.name)
        << " (rapid_runtime_cpp on Fast DDS).\n"
           "  --simulate          a simulated robot behind the handlers\n"
           "  --sim-speed X       simulated time runs X times faster (default 1)\n"
           "  --domain N          DDS domain (default "
        << t.domain
        << ")\n"
           "  --transport NAME    participant profile rapid_NAME of the QoS profiles: local (loopback only,\n"
           "                      the default), lan, wan, wan_tcp\n"
           "  --qos FILE          Fast DDS profiles to use instead of the built-in ones (the asset's\n"
           "                      generated qos/fastdds/rapid_qos_profiles.xml)\n"
           "  --seconds S         stop after S seconds (default: run until stopped)\n"
           "  --command-window N  commands remembered (repeated cmdIds, acks kept; default "
        << COMMAND_WINDOW
        << ")\n"
           "  --journal DIR       the restart journal's folder: commands accepted and not finished are\n"
           "                      answered after a crash (default "
        << Journal::default_dir()
        << ",\n"
           "                      from $RAPID_STATE_DIR, else $XDG_STATE_HOME/rapid_runtime)\n"
           "  --no-journal        no restart journal (a crash leaves commands unanswered)\n"
           "  --stop-timeout MS   how long a handler told to stop may run on before its command is\n"
           "                      answered EXEC_FAILED \"handler did not stop\" (default "
        << DEFAULT_STOP_TIMEOUT_MS
        << "; a command's\n"
           "                      stop_timeout_ms in the descriptor overrides it)\n"
           "  --shutdown-timeout MS  how long shutdown (Admin shutdown, SIGTERM, SIGINT) waits for the\n"
           "                      handlers before the process exits all the same (default "
        << DEFAULT_SHUTDOWN_TIMEOUT_MS << ")\n";
}

bool number(const std::string& text, double& out) {
    char* end = nullptr;
    out = std::strtod(text.c_str(), &end);
    return !text.empty() && end != nullptr && *end == '\0' && std::isfinite(out);
}

bool integer(const std::string& text, long long& out) {
    char* end = nullptr;
    out = std::strtoll(text.c_str(), &end, 10);
    return !text.empty() && end != nullptr && *end == '\0';
}

// false: usage error (said on stderr)
bool parse(int argc, char** argv, Args& a, bool& help) {
    for (int i = 1; i < argc; ++i) {
        std::string key = argv[i];
        if (key == "--help" || key == "-h") {
            help = true;
            return true;
        }
        if (key == "--simulate") {
            a.simulate = true;
            continue;
        }
        if (key == "--no-journal") {
            a.no_journal = true;
            continue;
        }
        if (i + 1 >= argc) {
            std::cerr << argv[0] << ": " << key << (key.rfind("--", 0) == 0 ? " needs a value" : ": unknown argument")
                      << "\n";
            return false;
        }
        std::string value = argv[++i];
        double x = 0;
        long long n = 0;
        bool ok = true;
        if (key == "--sim-speed") {
            ok = number(value, x) && x > 0;
            a.sim_speed = x;
        } else if (key == "--domain") {
            ok = integer(value, n) && n >= 0 && n <= 232;
            a.domain = static_cast<int>(n);
        } else if (key == "--transport") {
            ok = !value.empty();
            for (char c : value) ok = ok && (std::isalnum(static_cast<unsigned char>(c)) || c == '_');
            a.transport = value;
        } else if (key == "--qos") {
            ok = !value.empty();
            a.qos = value;
        } else if (key == "--seconds") {
            ok = number(value, x) && x >= 0;
            a.seconds = x;
        } else if (key == "--break") {
            ok = !value.empty();
            a.breaks.push_back(value);
        } else if (key == "--journal") {
            ok = !value.empty();
            a.journal = value;
        } else if (key == "--stop-timeout") {
            ok = integer(value, n) && n >= 1 && n <= 86'400'000;
            a.stop_timeout_ms = static_cast<int>(n);
        } else if (key == "--shutdown-timeout") {
            ok = integer(value, n) && n >= 0 && n <= 86'400'000;
            a.shutdown_timeout_ms = static_cast<int>(n);
        } else if (key == "--command-window") {
            ok = integer(value, n) && n >= 1;
            a.command_window = static_cast<std::size_t>(n);
        } else {
            std::cerr << argv[0] << ": unknown option " << visible(key) << "\n";
            return false;
        }
        if (!ok) {
            std::cerr << argv[0] << ": bad value for " << key << ": " << visible(value) << "\n";
            return false;
        }
    }
    return true;
}

}  // namespace

int run_bridge(int argc, char** argv, const Program& program) {
    const Tables& tables = *program.tables;
    const char* prog = argc > 0 ? argv[0] : "bridge";
    Args args;
    bool help = false;
    if (!parse(argc, argv, args, help)) {
        usage(std::cerr, prog, tables);
        return 2;
    }
    if (help) {
        usage(std::cout, prog, tables);
        return 0;
    }
    BridgeOptions options;
    options.domain = args.domain.value_or(tables.domain);
    options.transport = args.transport;
    options.command_window = args.command_window;
    options.breaks = args.breaks;
    options.stop_timeout_ms = args.stop_timeout_ms;
    options.shutdown_timeout_ms = args.shutdown_timeout_ms;
    if (!args.no_journal) options.journal = args.journal.empty() ? Journal::default_dir() : args.journal;
    if (args.qos.empty()) options.profiles_xml = std::string(program.profiles_xml);
    else options.profiles_file = args.qos;

    std::unique_ptr<Simulator> simulator;
    std::unique_ptr<BridgeHandlers> handlers;
    Handlers* serving = nullptr;
    if (args.simulate) {
        simulator = std::make_unique<Simulator>(tables, args.sim_speed);
        serving = simulator.get();
    } else {
        handlers = program.make_handlers ? program.make_handlers() : std::make_unique<BridgeHandlers>();
        serving = handlers.get();
    }
    try {
        Bridge bridge(tables, *serving, options);
        if (program.publish_configs) program.publish_configs(bridge);
        std::unique_ptr<SimulatedTelemetry> telemetry;
        if (simulator) {
            telemetry = std::make_unique<SimulatedTelemetry>(bridge, *simulator, program.custom);
            telemetry->prepare();
        }
        bridge.start();
        if (telemetry) telemetry->start();
        std::shared_ptr<void> streams;  // (stopped before the telemetry: its AgentState reads them)
        if (simulator && program.simulated_streams) streams = program.simulated_streams(bridge, *simulator);
        if (handlers) handlers->on_start(bridge);
        std::signal(SIGINT, on_signal);
        std::signal(SIGTERM, on_signal);
        std::cout << "bridge ready: asset " << visible(tables.name) << ", domain " << options.domain << ", partition "
                  << visible(tables.partition.empty() ? tables.name : tables.partition)
                  << (simulator ? ", simulated" : "") << std::endl;
        const auto end = args.seconds < 0 ? std::chrono::steady_clock::time_point::max()
                                          : std::chrono::steady_clock::now() +
                                                std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                                    std::chrono::duration<double>(args.seconds));
        while (!signalled && !bridge.wait(0.1) && std::chrono::steady_clock::now() < end) {
        }
        // Shutdown ends the process within its bound whatever the handlers do: the commands
        // are answered in bridge.stop(); should the user's on_stop() or anything else hang
        // past the bound and a grace, the process exits anyway (the journal answers then).
        const int bound = args.shutdown_timeout_ms;
        std::thread([bound, prog] {
            std::this_thread::sleep_for(std::chrono::milliseconds(bound) + std::chrono::seconds(10));
            std::cerr << prog << ": still stopping " << bound / 1000.0 + 10 << " s after shutdown began; exiting"
                      << std::endl;
            std::_Exit(0);
        }).detach();
        if (handlers) handlers->on_stop();
        streams.reset();
        if (telemetry) telemetry->stop();
        bridge.stop();
        if (bridge.handlers_running() > 0) {
            // every command is answered and the journal closed; the threads still in a handler
            // use the handlers and the manager, so the process ends here, without freeing them
            std::cout << "bridge stopped (" << bridge.handlers_running() << " handler(s) still running)" << std::endl;
            std::_Exit(0);
        }
    } catch (const std::exception& e) {
        std::cerr << prog << ": " << e.what() << std::endl;
        return 1;
    }
    std::cout << "bridge stopped" << std::endl;
    return 0;
}

}  // namespace dds
}  // namespace rapid_runtime
