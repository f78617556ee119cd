// XCDR1 reader and writer the generated encode/decode functions call (docs/cpp-backend.md).
// Every package carries the same copy under the same guard, so two packages can be
// included in one program. Its source is rapidgen's runtime/cpp/support/cdr.hpp: edit it there.
#ifndef RAPIDGEN_CDR_SUPPORT_V1
#define RAPIDGEN_CDR_SUPPORT_V1

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace rapidgen {
namespace cdr {

enum class Endianness { little, big };

#define RAPIDGEN_COLD __attribute__((noinline, cold))
#define RAPIDGEN_HOT __attribute__((always_inline))

constexpr Endianness host = __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__ ? Endianness::little : Endianness::big;

// Bad bytes: truncated, a count over its bound or over what the bytes can hold, a
// boolean not 0/1, an undeclared enumerator, a string without its NUL or not UTF-8.
class DecodeError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// A value the type cannot carry: a string or sequence over its bound.
class EncodeError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// Whether a NUL is among n bytes (8 at a time: inlined, cheaper than memchr on short text).
inline bool has_nul(const char* s, std::size_t n) noexcept {
    std::size_t i = 0;
    for (; n - i >= 8; i += 8) {
        std::uint64_t w;
        std::memcpy(&w, s + i, 8);
        if (((w - 0x0101010101010101ull) & ~w & 0x8080808080808080ull) != 0) return true;
    }
    for (; i < n; ++i) {
        if (s[i] == 0) return true;
    }
    return false;
}

template <class T>
inline T byteswap(T v) noexcept {
    unsigned char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    for (std::size_t i = 0; i < sizeof(T) / 2; ++i) {
        unsigned char t = b[i];
        b[i] = b[sizeof(T) - 1 - i];
        b[sizeof(T) - 1 - i] = t;
    }
    std::memcpy(&v, b, sizeof(T));
    return v;
}

// Writes into a buffer of known size (a Fast DDS payload, or a vector sized by Counter);
// Swap: the other byte order than the host's, fixed at compile time so every put is a
// plain store. Alignment counts from where the writer starts (after the 4-byte header).
template <bool Swap>
class BasicWriter {
public:
    BasicWriter(std::uint8_t* buf, std::size_t cap) : buf_(buf), cap_(cap) {}

    std::size_t size() const noexcept { return pos_; }

    RAPIDGEN_HOT void align(std::size_t n) {
        std::size_t pad = (n - pos_ % n) % n;
        if (pad != 0) std::memset(reserve(pad), 0, pad);
    }
    template <class T>
    RAPIDGEN_HOT void put(T v) {
        align(sizeof(T));
        if (Swap) v = byteswap(v);
        std::memcpy(reserve(sizeof(T)), &v, sizeof(T));
    }
    void put_bool(bool v) { put<std::uint8_t>(v ? 1 : 0); }
    RAPIDGEN_HOT void put_count(std::size_t n, std::size_t bound, const char* what) {
        if ((bound != 0 && n > bound) || n > 0xffffffffu) over(what, "elements", n, bound);
        put<std::uint32_t>(static_cast<std::uint32_t>(n));
    }
    RAPIDGEN_HOT void put_string(const std::string& s, std::size_t bound, const char* what) {
        if ((bound != 0 && s.size() > bound) || s.size() >= 0xffffffffu) over(what, "bytes", s.size(), bound);
        if (has_nul(s.data(), s.size())) over(what, "bytes, one a NUL", s.size(), bound);
        put<std::uint32_t>(static_cast<std::uint32_t>(s.size() + 1));
        std::uint8_t* p = reserve(s.size() + 1);
        std::memcpy(p, s.data(), s.size());
        p[s.size()] = 0;
    }
    // Numbers as one block (no padding before an empty run).
    template <class T>
    void put_array(const T* v, std::size_t n) {
        if (n == 0) return;
        align(sizeof(T));
        if (n > (cap_ - pos_) / sizeof(T)) overflow();
        std::uint8_t* p = reserve(n * sizeof(T));
        if (!Swap || sizeof(T) == 1) {
            std::memcpy(p, v, n * sizeof(T));
        } else {
            for (std::size_t i = 0; i < n; ++i) {
                T x = byteswap(v[i]);
                std::memcpy(p + i * sizeof(T), &x, sizeof(T));
            }
        }
    }

private:
    [[noreturn]] RAPIDGEN_COLD static void overflow() { throw EncodeError("the value does not fit the buffer"); }
    [[noreturn]] RAPIDGEN_COLD static void over(const char* what, const char* unit, std::size_t n, std::size_t bound) {
        throw EncodeError(std::string(what) + ": " + std::to_string(n) + " " + unit + ", bound " + std::to_string(bound));
    }
    RAPIDGEN_HOT std::uint8_t* reserve(std::size_t n) {
        if (n > cap_ - pos_) overflow();
        std::uint8_t* p = buf_ + pos_;
        pos_ += n;
        return p;
    }

    std::uint8_t* buf_;
    std::size_t cap_;
    std::size_t pos_ = 0;
};

// The host's byte order, and the other one.
using Writer = BasicWriter<false>;
using SwappedWriter = BasicWriter<true>;

// Counts the bytes a value takes (sizes the buffer before writing; Fast DDS's size provider).
class Counter {
public:
    std::size_t size() const noexcept { return pos_; }
    RAPIDGEN_HOT void align(std::size_t n) { pos_ += (n - pos_ % n) % n; }
    template <class T>
    void put(T) {
        align(sizeof(T));
        pos_ += sizeof(T);
    }
    void put_bool(bool) { put<std::uint8_t>(0); }
    void put_count(std::size_t, std::size_t, const char*) { put<std::uint32_t>(0); }
    void put_string(const std::string& s, std::size_t, const char*) {
        put<std::uint32_t>(0);
        pos_ += s.size() + 1;
    }
    template <class T>
    void put_array(const T*, std::size_t n) {
        if (n == 0) return;
        align(sizeof(T));
        pos_ += n * sizeof(T);
    }

private:
    std::size_t pos_ = 0;
};

// Reads what the writers write (Swap: the other byte order than the host's); every length
// is checked against the bound and against the bytes left before anything is allocated.
template <bool Swap>
class BasicReader {
public:
    BasicReader(const std::uint8_t* data, std::size_t size) : buf_(data), size_(size) {}

    std::size_t position() const noexcept { return pos_; }
    std::size_t left() const noexcept { return size_ - pos_; }
    [[noreturn]] RAPIDGEN_COLD void fail(const std::string& why) const {
        throw DecodeError(why + " at offset " + std::to_string(pos_));
    }
    RAPIDGEN_HOT void need(std::size_t n) const {
        if (n > size_ - pos_) fail_need(n);
    }
    RAPIDGEN_HOT void align(std::size_t n) {
        std::size_t pad = (n - pos_ % n) % n;
        need(pad);
        pos_ += pad;
    }
    template <class T>
    RAPIDGEN_HOT T get() {
        align(sizeof(T));
        need(sizeof(T));
        T v;
        std::memcpy(&v, buf_ + pos_, sizeof(T));
        pos_ += sizeof(T);
        return Swap ? byteswap(v) : v;
    }
    bool get_bool() {
        std::uint8_t b = get<std::uint8_t>();
        if (b > 1) fail_bool(b);
        return b == 1;
    }
    // A count of elements that take at least min_size bytes each.
    RAPIDGEN_HOT std::size_t get_count(std::size_t bound, std::size_t min_size, const char* what) {
        std::uint32_t n = get<std::uint32_t>();
        if ((bound != 0 && n > bound) || (min_size != 0 ? n > left() / min_size : n > 65536u)) fail_count(what, n, bound);
        return n;
    }
    RAPIDGEN_HOT void get_string(std::string& s, std::size_t bound, const char* what) {
        std::uint32_t n = get<std::uint32_t>();
        if (n == 0 || (bound != 0 && n - 1 > bound)) fail_string(what, n, bound);
        need(n);
        const char* p = reinterpret_cast<const char*>(buf_ + pos_);
        if (p[n - 1] != '\0' || !text(p, n - 1)) fail(std::string(what) + ": string not NUL-terminated, not UTF-8 or holding a NUL");
        s.assign(p, n - 1);
        pos_ += n;
    }
    template <class T>
    void get_array(T* v, std::size_t n) {
        if (n == 0) return;
        align(sizeof(T));
        if (n > left() / sizeof(T)) fail_need(n * sizeof(T));
        std::memcpy(static_cast<void*>(v), buf_ + pos_, n * sizeof(T));
        pos_ += n * sizeof(T);
        if (Swap && sizeof(T) > 1) {
            for (std::size_t i = 0; i < n; ++i) v[i] = byteswap(v[i]);
        }
    }
    template <class T>
    void get_vector(std::vector<T>& v, std::size_t bound, const char* what) {
        std::size_t n = get_count(bound, sizeof(T), what);
        v.resize(n);
        get_array(v.data(), n);
    }
    // Nesting of structs and unions (only recursive types get deep): at most 100 levels,
    // so hostile bytes cannot exhaust the stack.
    class Level {
    public:
        explicit Level(BasicReader& r) : r_(r) {
            if (++r_.depth_ > 100) r_.fail("nesting deeper than 100 levels");
        }
        ~Level() { --r_.depth_; }
        Level(const Level&) = delete;
        Level& operator=(const Level&) = delete;

    private:
        BasicReader& r_;
    };

    // The writer may pad the value to 4 bytes; anything more is an error.
    void finish() const {
        if (left() > 3) fail(std::to_string(left()) + " bytes after the value");
    }

private:
    // Failures build their messages out of line, so the checks stay small enough to inline.
    [[noreturn]] RAPIDGEN_COLD void fail_need(std::size_t n) const { fail("truncated: " + std::to_string(n) + " bytes needed"); }
    [[noreturn]] RAPIDGEN_COLD void fail_bool(unsigned b) const { fail("boolean " + std::to_string(b) + " is not 0 or 1"); }
    [[noreturn]] RAPIDGEN_COLD void fail_count(const char* what, std::size_t n, std::size_t bound) const {
        fail(std::string(what) + ": " + std::to_string(n) + " elements over the bound (" + std::to_string(bound) +
             ") or the bytes left");
    }
    [[noreturn]] RAPIDGEN_COLD void fail_string(const char* what, std::size_t n, std::size_t bound) const {
        fail(std::string(what) + ": string length " + std::to_string(n) + " (0, or over bound " + std::to_string(bound) + ")");
    }

    // Well-formed UTF-8 (RFC 3629: no overlong forms, surrogates or values over U+10FFFF)
    // without NUL; ASCII is checked 8 bytes at a time.
    static bool text(const char* s, std::size_t n) noexcept {
        const auto* p = reinterpret_cast<const unsigned char*>(s);
        std::size_t i = 0;
        while (i < n) {
            if (n - i >= 8) {
                std::uint64_t w;
                std::memcpy(&w, p + i, 8);
                const std::uint64_t high = 0x8080808080808080ull, ones = 0x0101010101010101ull;
                if ((w & high) == 0 && ((w - ones) & ~w & high) == 0) {
                    i += 8;
                    continue;
                }
            }
            unsigned c = p[i];
            if (c == 0) return false;
            if (c < 0x80) { ++i; continue; }
            std::size_t len = c >= 0xf0 ? 4 : c >= 0xe0 ? 3 : c >= 0xc0 ? 2 : 0;
            if (len == 0 || c > 0xf4 || c == 0xc0 || c == 0xc1 || len > n - i) return false;
            for (std::size_t k = 1; k < len; ++k) {
                if ((p[i + k] & 0xc0) != 0x80) return false;
            }
            unsigned c1 = p[i + 1];
            if ((c == 0xe0 && c1 < 0xa0) || (c == 0xed && c1 > 0x9f) || (c == 0xf0 && c1 < 0x90) ||
                (c == 0xf4 && c1 > 0x8f)) {
                return false;
            }
            i += len;
        }
        return true;
    }

    const std::uint8_t* buf_;
    std::size_t size_;
    std::size_t pos_ = 0;
    int depth_ = 0;
};

using Reader = BasicReader<false>;
using SwappedReader = BasicReader<true>;

// A whole sample: the 4-byte encapsulation header (CDR_BE 0x0000 / CDR_LE 0x0001), then the value.
template <class T>
std::vector<std::uint8_t> serialize(const T& value, Endianness e = Endianness::little) {
    Counter c;
    encode(c, value);
    std::vector<std::uint8_t> out(4 + c.size());
    out[1] = e == Endianness::little ? 1 : 0;
    if (e == host) {
        Writer w(out.data() + 4, c.size());
        encode(w, value);
    } else {
        SwappedWriter w(out.data() + 4, c.size());
        encode(w, value);
    }
    return out;
}

template <class T>
void deserialize(const std::uint8_t* data, std::size_t size, T& value) {
    if (size < 4) throw DecodeError("no encapsulation header");
    if (data[0] != 0 || data[1] > 1) {
        throw DecodeError("encapsulation " + std::to_string(data[0] * 256 + data[1]) +
                          " is not XCDR1 CDR_BE/CDR_LE");
    }
    if ((data[1] == 1) == (host == Endianness::little)) {
        Reader r(data + 4, size - 4);
        decode(r, value);
        r.finish();
    } else {
        SwappedReader r(data + 4, size - 4);
        decode(r, value);
        r.finish();
    }
}

template <class T>
T deserialize(const std::vector<std::uint8_t>& bytes) {
    T value;
    deserialize(bytes.data(), bytes.size(), value);
    return value;
}

}  // namespace cdr
}  // namespace rapidgen

#endif  // RAPIDGEN_CDR_SUPPORT_V1
