// Ack, queue and record vocabulary: the RAPID IDL's enumerators, in the IDL's order, so
// the DDS layer converts with a static_cast (rapid-protocol.md section 4).
#ifndef RAPID_RUNTIME_VOCABULARY_HPP
#define RAPID_RUNTIME_VOCABULARY_HPP

#include <cstdint>
#include <string_view>

namespace rapid_runtime {

enum class AckStatus : std::int32_t { Queued, Executing, Requeued, Completed };
enum class Completion : std::int32_t { Not, Ok, BadSyntax, ExecFailed, Canceled };
enum class QueueAction : std::int32_t { Bypass, Append, Delete, Insert, Replace };
enum class RecordResult : std::int32_t { Init, Succeeded, Failed };
enum class RecordStatus : std::int32_t {
    Init, Outbound, Lost, Inline, Preempted, InProcess, Paused, Canceled, Succeeded, Failed,
    AlienPending, AlienActive, AlienCompleted, ForgottenByRobot
};

// INSERT's target naming the front of the queue (rapid-protocol.md section 4).
inline constexpr std::string_view HEAD = "head";

std::string_view name_of(AckStatus s);
std::string_view name_of(Completion c);
std::string_view name_of(QueueAction a);  // "QUEUE_BYPASS" ...; "" for a value outside the enum
std::string_view name_of(RecordStatus s);

// Ack -> QueueState record (rapid-protocol.md 5b).
RecordStatus status_of(Completion c);
RecordResult result_of(Completion c);

}  // namespace rapid_runtime

#endif
