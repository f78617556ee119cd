// Text that reaches an Ack or a log: names from the wire shortened and escaped, messages
// cut to Ack.message's 127 bytes on a character boundary.
#ifndef RAPID_RUNTIME_TEXT_HPP
#define RAPID_RUNTIME_TEXT_HPP

#include <cstddef>
#include <string>
#include <string_view>

namespace rapid_runtime {

// Ack.message is a String128: at most 127 bytes on the wire (Astrobee copies 128 bytes
// unterminated, so a full 128 would lose its terminator there).
inline constexpr std::size_t MESSAGE_BYTES = 127;

// text cut to at most `limit` UTF-8 bytes, never inside a character.
std::string clip(std::string_view text, std::size_t limit = MESSAGE_BYTES);

// text as valid UTF-8 without NUL: each maximal invalid subsequence (the Unicode standard's
// "maximal subpart", as Python's bytes.decode(errors="replace") does) and each NUL becomes
// U+FFFD. Valid text comes back unchanged.
std::string valid_utf8(std::string_view text);

// What the runtime writes into a bounded IDL string (Ack.message, a progress text, a
// TextMessage): valid_utf8(text) clipped to `limit` bytes on a character boundary. Every
// ground tool decodes it, and no NUL cuts it short or stops it from being written.
std::string outgoing(std::string_view text, std::size_t limit = MESSAGE_BYTES);

// A name from the wire, readable within 127 bytes: when any character is not printable
// (or the bytes are not UTF-8), the whole name is escaped as Python's unicode_escape does;
// then cut to n characters, the last three "...".
std::string shorten(std::string_view text, std::size_t n = 24);

// Every character printable: control characters (C0, DEL, C1) and invalid UTF-8 are not.
bool printable(std::string_view text);

// For logs: text with every non-printable byte escaped, at most `limit` characters.
std::string visible(std::string_view text, std::size_t limit = 200);

}  // namespace rapid_runtime

#endif
