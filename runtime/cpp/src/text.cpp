#include "rapid_runtime/text.hpp"

#include <cstdint>
#include <cstdio>
#include <vector>

namespace rapid_runtime {
namespace {

// Code points of UTF-8 text; false when the bytes are not UTF-8.
bool decode(std::string_view text, std::vector<char32_t>& out) {
    const auto* p = reinterpret_cast<const unsigned char*>(text.data());
    const auto* end = p + text.size();
    while (p < end) {
        unsigned char c = *p;
        int n = c < 0x80 ? 0 : (c >> 5) == 6 ? 1 : (c >> 4) == 14 ? 2 : (c >> 3) == 30 ? 3 : -1;
        if (n < 0 || end - p <= n) return false;
        char32_t cp = n == 0 ? c : n == 1 ? (c & 0x1f) : n == 2 ? (c & 0x0f) : (c & 0x07);
        for (int i = 1; i <= n; ++i) {
            if ((p[i] & 0xc0) != 0x80) return false;
            cp = (cp << 6) | (p[i] & 0x3f);
        }
        static constexpr char32_t least[] = {0, 0x80, 0x800, 0x10000};
        if (cp < least[n] || cp > 0x10ffff || (cp >= 0xd800 && cp <= 0xdfff)) return false;
        out.push_back(cp);
        p += n + 1;
    }
    return true;
}

// Python's str.isprintable, approximated: controls, separators other than the space,
// format characters, private use and noncharacters are not printable.
bool printable_cp(char32_t c) {
    if (c < 0x20 || (c >= 0x7f && c <= 0xa0) || c == 0xad) return false;
    if ((c >= 0x2000 && c <= 0x200f) || (c >= 0x2028 && c <= 0x202f) || (c >= 0x205f && c <= 0x206f)) return false;
    if (c == 0x1680 || c == 0x3000 || c == 0xfeff || (c >= 0xfff9 && c <= 0xfffb)) return false;
    if ((c >= 0xe000 && c <= 0xf8ff) || c >= 0xf0000 || (c & 0xfffe) == 0xfffe) return false;
    if (c >= 0xe0000 && c <= 0xe007f) return false;
    return true;
}

void hex(std::string& out, const char* prefix, unsigned long value, int digits) {
    char buf[16];
    std::snprintf(buf, sizeof buf, "%s%0*lx", prefix, digits, value);
    out += buf;
}

// As Python's unicode_escape.
std::string escape(const std::vector<char32_t>& cps) {
    std::string out;
    for (char32_t c : cps) {
        if (c == '\\') out += "\\\\";
        else if (c == '\t') out += "\\t";
        else if (c == '\n') out += "\\n";
        else if (c == '\r') out += "\\r";
        else if (c >= 0x20 && c < 0x7f) out += static_cast<char>(c);
        else if (c < 0x100) hex(out, "\\x", c, 2);
        else if (c < 0x10000) hex(out, "\\u", c, 4);
        else hex(out, "\\U", c, 8);
    }
    return out;
}

}  // namespace

std::string clip(std::string_view text, std::size_t limit) {
    if (text.size() <= limit) return std::string(text);
    std::size_t cut = limit;
    while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xc0) == 0x80) --cut;
    return std::string(text.substr(0, cut));
}

std::string valid_utf8(std::string_view text) {
    static constexpr char REPLACEMENT[] = "\xef\xbf\xbd";  // U+FFFD
    const auto* p = reinterpret_cast<const unsigned char*>(text.data());
    const std::size_t n = text.size();
    std::string out;
    out.reserve(n);
    std::size_t i = 0;
    while (i < n) {
        const unsigned char c = p[i];
        if (c == 0) {
            out += REPLACEMENT;
            ++i;
            continue;
        }
        if (c < 0x80) {
            out += static_cast<char>(c);
            ++i;
            continue;
        }
        // The lead byte's sequence length and the range its second byte must be in (Unicode
        // Table 3-7, well-formed UTF-8: no overlong form, no surrogate, nothing past U+10FFFF).
        int need = 0;
        unsigned char lo = 0x80, hi = 0xbf;
        if (c >= 0xc2 && c <= 0xdf) need = 1;
        else if (c == 0xe0) need = 2, lo = 0xa0;
        else if (c >= 0xe1 && c <= 0xec) need = 2;
        else if (c == 0xed) need = 2, hi = 0x9f;
        else if (c >= 0xee && c <= 0xef) need = 2;
        else if (c == 0xf0) need = 3, lo = 0x90;
        else if (c >= 0xf1 && c <= 0xf3) need = 3;
        else if (c == 0xf4) need = 3, hi = 0x8f;
        if (need == 0) {  // a continuation byte alone, or a byte never in UTF-8
            out += REPLACEMENT;
            ++i;
            continue;
        }
        std::size_t j = i + 1;
        int got = 0;
        while (got < need && j < n) {
            const unsigned char b = p[j];
            const bool ok = got == 0 ? (b >= lo && b <= hi) : (b >= 0x80 && b <= 0xbf);
            if (!ok) break;
            ++j;
            ++got;
        }
        if (got == need) out.append(text.data() + i, j - i);
        else out += REPLACEMENT;  // the maximal subpart i..j, one U+FFFD; go on at the byte that broke it
        i = j;
    }
    return out;
}

std::string outgoing(std::string_view text, std::size_t limit) { return clip(valid_utf8(text), limit); }

bool printable(std::string_view text) {
    std::vector<char32_t> cps;
    if (!decode(text, cps)) return false;
    for (char32_t c : cps)
        if (!printable_cp(c)) return false;
    return true;
}

std::string shorten(std::string_view text, std::size_t n) {
    std::vector<char32_t> cps;
    bool utf8 = decode(text, cps);
    bool plain = utf8;
    for (char32_t c : cps) plain = plain && printable_cp(c);
    if (!plain) {
        if (!utf8) {  // not from a decoded sample; each byte stands for itself
            cps.clear();
            for (char ch : text) cps.push_back(static_cast<unsigned char>(ch));
        }
        std::string escaped = escape(cps);
        cps.assign(escaped.begin(), escaped.end());
    }
    if (cps.size() > n) {
        cps.resize(n >= 3 ? n - 3 : 0);
        cps.insert(cps.end(), {'.', '.', '.'});
    }
    std::string out;
    for (char32_t c : cps) {  // back to UTF-8
        if (c < 0x80) {
            out += static_cast<char>(c);
        } else if (c < 0x800) {
            out += static_cast<char>(0xc0 | (c >> 6));
            out += static_cast<char>(0x80 | (c & 0x3f));
        } else if (c < 0x10000) {
            out += static_cast<char>(0xe0 | (c >> 12));
            out += static_cast<char>(0x80 | ((c >> 6) & 0x3f));
            out += static_cast<char>(0x80 | (c & 0x3f));
        } else {
            out += static_cast<char>(0xf0 | (c >> 18));
            out += static_cast<char>(0x80 | ((c >> 12) & 0x3f));
            out += static_cast<char>(0x80 | ((c >> 6) & 0x3f));
            out += static_cast<char>(0x80 | (c & 0x3f));
        }
    }
    return out;
}

std::string visible(std::string_view text, std::size_t limit) {
    std::string out;
    for (char ch : text) {
        auto c = static_cast<unsigned char>(ch);
        if (c == '\\') out += "\\\\";
        else if (c >= 0x20 && c < 0x7f) out += ch;
        else hex(out, "\\x", c, 2);
        if (out.size() >= limit) {
            out.resize(limit);
            out += "...";
            break;
        }
    }
    return out;
}

}  // namespace rapid_runtime
