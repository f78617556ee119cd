//! Text that reaches an Ack or a log: names from the wire shortened and escaped, messages cut
//! to Ack.message's 127 bytes on a character boundary (runtime/rapid_runtime/acks.py and
//! validate.py are the reference).

/// Ack.message is a String128: at most 127 bytes on the wire (Astrobee copies 128 bytes
/// unterminated, so a full 128 would lose its terminator there).
pub const MESSAGE_BYTES: usize = 127;

/// text cut to at most `limit` UTF-8 bytes, never inside a character.
pub fn clip(text: &str, limit: usize) -> &str {
    if text.len() <= limit {
        return text;
    }
    let mut cut = limit;
    while !text.is_char_boundary(cut) {
        cut -= 1;
    }
    &text[..cut]
}

/// What the runtime writes into a bounded IDL string: each NUL (it ends a C string on the
/// other side of the wire) made U+FFFD, then clipped. (A Rust string is valid UTF-8 already:
/// the DDS layer decodes what it reads with replacement.)
pub fn outgoing(text: &str, limit: usize) -> String {
    if text.contains('\0') {
        clip(&text.replace('\0', "\u{fffd}"), limit).to_string()
    } else {
        clip(text, limit).to_string()
    }
}

/// Python's str.isprintable, approximated as the C++ runtime does: controls, separators other
/// than the space, format characters, private use and noncharacters are not printable.
fn printable_char(c: char) -> bool {
    let c = c as u32;
    if c < 0x20 || (0x7f..=0xa0).contains(&c) || c == 0xad {
        return false;
    }
    if (0x2000..=0x200f).contains(&c) || (0x2028..=0x202f).contains(&c) || (0x205f..=0x206f).contains(&c) {
        return false;
    }
    if c == 0x1680 || c == 0x3000 || c == 0xfeff || (0xfff9..=0xfffb).contains(&c) {
        return false;
    }
    if (0xe000..=0xf8ff).contains(&c) || c >= 0xf0000 || (c & 0xfffe) == 0xfffe {
        return false;
    }
    !(0xe0000..=0xe007f).contains(&c)
}

pub fn printable(text: &str) -> bool {
    text.chars().all(printable_char)
}

/// As Python's unicode_escape.
fn escape(text: &str) -> String {
    let mut out = String::new();
    for c in text.chars() {
        let n = c as u32;
        match c {
            '\\' => out.push_str("\\\\"),
            '\t' => out.push_str("\\t"),
            '\n' => out.push_str("\\n"),
            '\r' => out.push_str("\\r"),
            _ if (0x20..0x7f).contains(&n) => out.push(c),
            _ if n < 0x100 => out.push_str(&format!("\\x{n:02x}")),
            _ if n < 0x10000 => out.push_str(&format!("\\u{n:04x}")),
            _ => out.push_str(&format!("\\U{n:08x}")),
        }
    }
    out
}

/// A name from the wire, readable within 127 bytes: when any character is not printable the
/// whole name is escaped as Python's unicode_escape does; then cut to n characters, the last
/// three "...".
pub fn shorten(text: &str, n: usize) -> String {
    let shown = if printable(text) { text.to_string() } else { escape(text) };
    if shown.chars().count() <= n {
        return shown;
    }
    let kept: String = shown.chars().take(n.saturating_sub(3)).collect();
    kept + "..."
}

/// shorten() at the reasons' usual 24 characters.
pub fn short(text: &str) -> String {
    shorten(text, 24)
}

/// For logs: text with every character outside printable ASCII escaped, at most `limit` characters.
pub fn visible(text: &str, limit: usize) -> String {
    let mut out = String::new();
    for c in text.chars() {
        match c {
            '\\' => out.push_str("\\\\"),
            ' '..='~' => out.push(c),
            _ => out.push_str(&escape(&c.to_string()).replace("\\\\", "\\")),
        }
        if out.len() >= limit {
            out.truncate(limit);
            out.push_str("...");
            break;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clip_keeps_whole_characters() {
        let s = "é".repeat(100);
        assert_eq!(clip(&s, 127).len(), 126);
        assert_eq!(outgoing("a\0b", 127), "a\u{fffd}b");
    }

    #[test]
    fn shorten_escapes_and_cuts() {
        assert_eq!(short("Arm"), "Arm");
        assert_eq!(short("a\nb"), "a\\nb");
        assert_eq!(shorten("abcdefghij", 8), "abcde...");
        assert_eq!(visible("a\u{1}", 200), "a\\x01");
    }
}
