#include "rapid_runtime/vocabulary.hpp"

namespace rapid_runtime {

std::string_view name_of(AckStatus s) {
    switch (s) {
        case AckStatus::Queued: return "ACK_QUEUED";
        case AckStatus::Executing: return "ACK_EXECUTING";
        case AckStatus::Requeued: return "ACK_REQUEUED";
        case AckStatus::Completed: return "ACK_COMPLETED";
    }
    return "";
}

std::string_view name_of(Completion c) {
    switch (c) {
        case Completion::Not: return "ACK_COMPLETED_NOT";
        case Completion::Ok: return "ACK_COMPLETED_OK";
        case Completion::BadSyntax: return "ACK_COMPLETED_BAD_SYNTAX";
        case Completion::ExecFailed: return "ACK_COMPLETED_EXEC_FAILED";
        case Completion::Canceled: return "ACK_COMPLETED_CANCELED";
    }
    return "";
}

std::string_view name_of(QueueAction a) {
    switch (a) {
        case QueueAction::Bypass: return "QUEUE_BYPASS";
        case QueueAction::Append: return "QUEUE_APPEND";
        case QueueAction::Delete: return "QUEUE_DELETE";
        case QueueAction::Insert: return "QUEUE_INSERT";
        case QueueAction::Replace: return "QUEUE_REPLACE";
    }
    return "";
}

std::string_view name_of(RecordStatus s) {
    static constexpr std::string_view names[] = {
        "Q_STATUS_INIT", "Q_STATUS_OUTBOUND", "Q_STATUS_LOST", "Q_STATUS_INLINE", "Q_STATUS_PREEMPTED",
        "Q_STATUS_INPROCESS", "Q_STATUS_PAUSED", "Q_STATUS_CANCELED", "Q_STATUS_SUCCEEDED", "Q_STATUS_FAILED",
        "Q_STATUS_ALIEN_PENDING", "Q_STATUS_ALIEN_ACTIVE", "Q_STATUS_ALIEN_COMPLETED", "Q_STATUS_FORGOTTEN_BY_ROBOT"};
    auto i = static_cast<std::size_t>(s);
    return i < sizeof(names) / sizeof(names[0]) ? names[i] : "";
}

RecordStatus status_of(Completion c) {
    switch (c) {
        case Completion::Ok: return RecordStatus::Succeeded;
        case Completion::BadSyntax:
        case Completion::ExecFailed: return RecordStatus::Failed;
        case Completion::Canceled: return RecordStatus::Canceled;
        case Completion::Not: break;
    }
    return RecordStatus::Init;
}

RecordResult result_of(Completion c) {
    return c == Completion::Ok ? RecordResult::Succeeded : c == Completion::Not ? RecordResult::Init
                                                                                 : RecordResult::Failed;
}

}  // namespace rapid_runtime
