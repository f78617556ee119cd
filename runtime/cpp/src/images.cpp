#include "rapid_runtime/images.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>

namespace rapid_runtime {
namespace {

constexpr int BLOCK = 8;
constexpr double TAU = 6.283185307179586;

struct Rgb {
    int r, g, b;
};

std::string lower(std::string s) {
    for (auto& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

enum class Kind { None, Png, Jpeg, Bmp, Pgm, Ppm };

Kind kind_of(const std::string& mime) {
    static const std::map<std::string, Kind> kinds = {
        {"image/png", Kind::Png},       {"image/jpeg", Kind::Jpeg},         {"image/jpg", Kind::Jpeg},
        {"image/pjpeg", Kind::Jpeg},    {"image/bmp", Kind::Bmp},           {"image/x-bmp", Kind::Bmp},
        {"image/x-ms-bmp", Kind::Bmp},  {"image/x-portable-graymap", Kind::Pgm},
        {"image/x-portable-pixmap", Kind::Ppm}, {"image/x-portable-anymap", Kind::Ppm}};
    auto found = kinds.find(lower(mime));
    return found == kinds.end() ? Kind::None : found->second;
}

// A fixed pseudo-random 0..65535 per block (the same rock is seen again from the same heading).
int noise(int i, int j) {
    std::uint32_t h = (static_cast<std::uint32_t>(i) * 73856093u) ^ (static_cast<std::uint32_t>(j) * 19349663u) ^
                      0x5BD1E995u;
    h = (h ^ (h >> 13)) * 0x5BD1E995u;
    return static_cast<int>((h ^ (h >> 15)) & 0xFFFFu);
}

// bh rows of bw blocks: the landscape seen from heading, frame in binary bottom left.
std::vector<std::vector<Rgb>> scene(int bw, int bh, double heading, std::uint32_t frame) {
    int horizon = std::max(1, static_cast<int>(bh * 0.45));
    int shift = static_cast<int>(std::nearbyint(heading / TAU * bw * 4));
    double sun_c = std::fmod(0.7 * bw - heading / TAU * bw * 4, bw * 4.0);
    if (sun_c < 0) sun_c += bw * 4.0;
    int sun_r = std::max(0, horizon / 3);
    double sun_rad = std::max(1.0, bw / 24.0);
    std::vector<std::vector<Rgb>> rows(static_cast<std::size_t>(bh), std::vector<Rgb>(static_cast<std::size_t>(bw)));
    for (int r = 0; r < bh; ++r) {
        auto& row = rows[static_cast<std::size_t>(r)];
        if (r < horizon) {  // sky: deep blue above, pale at the horizon
            double t = static_cast<double>(r) / horizon;
            Rgb base{static_cast<int>(70 + 110 * t), static_cast<int>(120 + 90 * t), static_cast<int>(200 + 40 * t)};
            for (int c = 0; c < bw; ++c)
                row[static_cast<std::size_t>(c)] =
                    std::hypot(c - sun_c, r - sun_r) <= sun_rad ? Rgb{255, 244, 200} : base;
        } else {  // ground: ochre, darker towards the viewer, scattered rocks
            double t = static_cast<double>(r - horizon) / std::max(1, bh - horizon);
            for (int c = 0; c < bw; ++c) {
                int n = noise(c + shift, r);
                int shade = static_cast<int>(20 * (n & 0xFF) / 255.0) - 10;
                Rgb g{static_cast<int>(170 - 60 * t) + shade, static_cast<int>(120 - 45 * t) + shade,
                      static_cast<int>(80 - 30 * t) + shade};
                if ((n >> 8) < std::max(2, static_cast<int>(12 * t))) g = Rgb{g.r / 2, g.g / 2, g.b / 2};
                row[static_cast<std::size_t>(c)] = g;
            }
        }
    }
    int bits = std::min(16, bw);
    for (int bit = 0; bit < bits; ++bit)
        rows[static_cast<std::size_t>(bh - 1)][static_cast<std::size_t>(bit)] =
            (frame >> (bits - 1 - bit)) & 1u ? Rgb{255, 255, 255} : Rgb{0, 0, 0};
    return rows;
}

int clamp255(double v) { return std::max(0, std::min(255, static_cast<int>(v))); }
int grey_of(const Rgb& c) { return clamp255(0.299 * c.r + 0.587 * c.g + 0.114 * c.b + 0.5); }

// One pixel row of the block grid, cut to width.
std::vector<std::uint8_t> pixel_row(const std::vector<Rgb>& blocks, int width, bool grey) {
    std::vector<std::uint8_t> line;
    line.reserve(static_cast<std::size_t>(width) * (grey ? 1 : 3));
    for (int x = 0; x < width; ++x) {
        const Rgb& c = blocks[static_cast<std::size_t>(x / BLOCK)];
        if (grey) {
            line.push_back(static_cast<std::uint8_t>(grey_of(c)));
        } else {
            line.push_back(static_cast<std::uint8_t>(clamp255(c.r)));
            line.push_back(static_cast<std::uint8_t>(clamp255(c.g)));
            line.push_back(static_cast<std::uint8_t>(clamp255(c.b)));
        }
    }
    return line;
}

void put32be(std::vector<std::uint8_t>& out, std::uint32_t v) {
    for (int s = 24; s >= 0; s -= 8) out.push_back(static_cast<std::uint8_t>(v >> s));
}
void put16be(std::vector<std::uint8_t>& out, unsigned v) {
    out.push_back(static_cast<std::uint8_t>(v >> 8));
    out.push_back(static_cast<std::uint8_t>(v));
}
void put32le(std::vector<std::uint8_t>& out, std::uint32_t v) {
    for (int s = 0; s < 32; s += 8) out.push_back(static_cast<std::uint8_t>(v >> s));
}
void put16le(std::vector<std::uint8_t>& out, unsigned v) {
    out.push_back(static_cast<std::uint8_t>(v));
    out.push_back(static_cast<std::uint8_t>(v >> 8));
}

// ---- PNG: zlib stream of one fixed-Huffman deflate block ----------------------------------

std::uint32_t crc32(const std::uint8_t* p, std::size_t n, std::uint32_t crc = 0) {
    static const auto table = [] {
        std::array<std::uint32_t, 256> t{};
        for (std::uint32_t i = 0; i < 256; ++i) {
            std::uint32_t c = i;
            for (int k = 0; k < 8; ++k) c = c & 1 ? 0xEDB88320u ^ (c >> 1) : c >> 1;
            t[i] = c;
        }
        return t;
    }();
    crc = ~crc;
    for (std::size_t i = 0; i < n; ++i) crc = table[(crc ^ p[i]) & 0xFF] ^ (crc >> 8);
    return ~crc;
}

class BitWriter {
public:
    explicit BitWriter(std::vector<std::uint8_t>& out) : out_(out) {}
    void bits(std::uint32_t value, int count) {  // least significant bit first
        for (int i = 0; i < count; ++i) put((value >> i) & 1u);
    }
    void code(std::uint32_t code, int length) {  // Huffman codes: most significant bit first
        for (int i = length - 1; i >= 0; --i) put((code >> i) & 1u);
    }
    void flush() {
        if (n_ > 0) out_.push_back(static_cast<std::uint8_t>(acc_));
        acc_ = 0;
        n_ = 0;
    }

private:
    void put(std::uint32_t bit) {
        acc_ |= bit << n_;
        if (++n_ == 8) flush();
    }
    std::vector<std::uint8_t>& out_;
    std::uint32_t acc_ = 0;
    int n_ = 0;
};

void literal(BitWriter& w, unsigned v) {  // the fixed literal/length code (RFC 1951 3.2.6)
    if (v < 144) w.code(0x30 + v, 8);
    else if (v < 256) w.code(0x190 + v - 144, 9);
    else if (v < 280) w.code(v - 256, 7);
    else w.code(0xC0 + v - 280, 8);
}

void match(BitWriter& w, unsigned length, unsigned distance) {
    static const unsigned LBASE[] = {3, 4, 5, 6, 7, 8, 9, 10, 11, 13, 15, 17, 19, 23, 27, 31,
                                     35, 43, 51, 59, 67, 83, 99, 115, 131, 163, 195, 227, 258};
    static const int LEXTRA[] = {0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 2, 3, 3, 3, 3, 4, 4, 4, 4, 5, 5, 5, 5, 0};
    static const unsigned DBASE[] = {1, 2, 3, 4, 5, 7, 9, 13, 17, 25, 33, 49, 65, 97, 129, 193,
                                     257, 385, 513, 769, 1025, 1537, 2049, 3073, 4097, 6145, 8193, 12289, 16385, 24577};
    static const int DEXTRA[] = {0, 0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 5, 5, 6, 6,
                                 7, 7, 8, 8, 9, 9, 10, 10, 11, 11, 12, 12, 13, 13};
    int l = 28;
    while (LBASE[l] > length) --l;
    literal(w, 257 + static_cast<unsigned>(l));
    w.bits(length - LBASE[l], LEXTRA[l]);
    int d = 29;
    while (DBASE[d] > distance) --d;
    w.code(static_cast<std::uint32_t>(d), 5);
    w.bits(distance - DBASE[d], DEXTRA[d]);
}

// zlib (RFC 1950) of raw: matches one pixel back (bpp) or one row back (stride) only, which
// is what a block picture repeats.
std::vector<std::uint8_t> zlib_stream(const std::vector<std::uint8_t>& raw, std::size_t bpp, std::size_t stride) {
    std::vector<std::uint8_t> out{0x78, 0x01};
    BitWriter w(out);
    w.bits(1, 1);  // final block
    w.bits(1, 2);  // fixed Huffman codes
    const std::size_t n = raw.size();
    std::size_t i = 0;
    while (i < n) {
        std::size_t best = 0, dist = 0;
        for (std::size_t d : {stride, bpp}) {
            if (d == 0 || d > 32768 || d > i) continue;
            std::size_t len = 0;
            while (len < 258 && i + len < n && raw[i + len] == raw[i + len - d]) ++len;
            if (len > best) best = len, dist = d;
        }
        if (best >= 3) {
            match(w, static_cast<unsigned>(best), static_cast<unsigned>(dist));
            i += best;
        } else {
            literal(w, raw[i]);
            ++i;
        }
    }
    literal(w, 256);  // end of block
    w.flush();
    std::uint32_t a = 1, b = 0;  // Adler-32
    for (auto byte : raw) {
        a = (a + byte) % 65521u;
        b = (b + a) % 65521u;
    }
    put32be(out, (b << 16) | a);
    return out;
}

void chunk(std::vector<std::uint8_t>& out, const char* kind, const std::vector<std::uint8_t>& body) {
    put32be(out, static_cast<std::uint32_t>(body.size()));
    std::vector<std::uint8_t> typed(kind, kind + 4);
    typed.insert(typed.end(), body.begin(), body.end());
    out.insert(out.end(), typed.begin(), typed.end());
    put32be(out, crc32(typed.data(), typed.size()));
}

std::vector<std::uint8_t> png(const std::vector<std::vector<Rgb>>& blocks, int width, int height, bool grey) {
    std::size_t px = grey ? 1 : 3, stride = 1 + px * static_cast<std::size_t>(width);
    std::vector<std::uint8_t> raw;
    raw.reserve(stride * static_cast<std::size_t>(height));
    std::vector<std::uint8_t> line;
    for (int y = 0; y < height; ++y) {
        if (y % BLOCK == 0) line = pixel_row(blocks[static_cast<std::size_t>(y / BLOCK)], width, grey);
        raw.push_back(0);  // filter: none
        raw.insert(raw.end(), line.begin(), line.end());
    }
    std::vector<std::uint8_t> out{0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    std::vector<std::uint8_t> ihdr;
    put32be(ihdr, static_cast<std::uint32_t>(width));
    put32be(ihdr, static_cast<std::uint32_t>(height));
    ihdr.insert(ihdr.end(), {8, static_cast<std::uint8_t>(grey ? 0 : 2), 0, 0, 0});
    chunk(out, "IHDR", ihdr);
    chunk(out, "IDAT", zlib_stream(raw, px, stride));
    chunk(out, "IEND", {});
    return out;
}

// ---- JPEG: baseline, one DC coefficient per block, every AC coefficient zero ----------------

const std::uint8_t DC_BITS[16] = {0, 1, 5, 1, 1, 1, 1, 1, 1, 0, 0, 0, 0, 0, 0, 0};
const std::uint8_t AC_BITS[16] = {1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
constexpr int DC_QUANT = 8;

void segment(std::vector<std::uint8_t>& out, std::uint8_t marker, const std::vector<std::uint8_t>& body) {
    out.push_back(0xFF);
    out.push_back(marker);
    put16be(out, static_cast<unsigned>(body.size() + 2));
    out.insert(out.end(), body.begin(), body.end());
}

class JpegBits {
public:
    explicit JpegBits(std::vector<std::uint8_t>& out) : out_(out) {}
    void put(std::uint32_t code, int length) {
        for (int i = length - 1; i >= 0; --i) {
            acc_ = static_cast<std::uint8_t>((acc_ << 1) | ((code >> i) & 1u));
            if (++n_ == 8) emit();
        }
    }
    void finish() {  // pad with 1s
        while (n_ != 0) put(1, 1);
    }

private:
    void emit() {
        out_.push_back(acc_);
        if (acc_ == 0xFF) out_.push_back(0x00);  // byte stuffing
        acc_ = 0;
        n_ = 0;
    }
    std::vector<std::uint8_t>& out_;
    std::uint8_t acc_ = 0;
    int n_ = 0;
};

std::vector<std::uint8_t> jpeg(const std::vector<std::vector<Rgb>>& blocks, int width, int height, bool grey) {
    // DC codes (ITU T.81 K.3): category -> (code, length)
    std::array<std::pair<std::uint32_t, int>, 12> dc{};
    {
        std::uint32_t code = 0;
        int k = 0;
        for (int length = 1; length <= 16; ++length) {
            for (int c = 0; c < DC_BITS[length - 1]; ++c) dc[static_cast<std::size_t>(k++)] = {code++, length};
            code <<= 1;
        }
    }
    const int ncomp = grey ? 1 : 3;
    std::vector<std::uint8_t> out{0xFF, 0xD8};
    segment(out, 0xE0, {'J', 'F', 'I', 'F', 0, 1, 1, 0, 0, 1, 0, 1, 0, 0});
    std::vector<std::uint8_t> quant{0, DC_QUANT};
    quant.resize(65, 16);
    segment(out, 0xDB, quant);
    std::vector<std::uint8_t> sof{8};
    put16be(sof, static_cast<unsigned>(height));
    put16be(sof, static_cast<unsigned>(width));
    sof.push_back(static_cast<std::uint8_t>(ncomp));
    for (int k = 0; k < ncomp; ++k) sof.insert(sof.end(), {static_cast<std::uint8_t>(k + 1), 0x11, 0});
    segment(out, 0xC0, sof);
    std::vector<std::uint8_t> dht{0x00};
    dht.insert(dht.end(), DC_BITS, DC_BITS + 16);
    for (std::uint8_t v = 0; v < 12; ++v) dht.push_back(v);
    segment(out, 0xC4, dht);
    std::vector<std::uint8_t> aht{0x10};
    aht.insert(aht.end(), AC_BITS, AC_BITS + 16);
    aht.push_back(0x00);
    segment(out, 0xC4, aht);
    std::vector<std::uint8_t> sos{static_cast<std::uint8_t>(ncomp)};
    for (int k = 0; k < ncomp; ++k) sos.insert(sos.end(), {static_cast<std::uint8_t>(k + 1), 0x00});
    sos.insert(sos.end(), {0x00, 0x3F, 0x00});
    segment(out, 0xDA, sos);
    JpegBits bits(out);
    int pred[3] = {0, 0, 0};
    auto clamp127 = [](double v) { return std::max(-127, std::min(127, static_cast<int>(std::lround(v)))); };
    for (const auto& row : blocks) {
        for (const auto& c : row) {
            int v[3];
            if (grey) {
                v[0] = std::max(-127, std::min(127, grey_of(c) - 128));
            } else {
                v[0] = clamp127(0.299 * c.r + 0.587 * c.g + 0.114 * c.b - 128);
                v[1] = clamp127(-0.168736 * c.r - 0.331264 * c.g + 0.5 * c.b);
                v[2] = clamp127(0.5 * c.r - 0.418688 * c.g - 0.081312 * c.b);
            }
            for (int k = 0; k < ncomp; ++k) {  // one block per component per MCU
                int diff = v[k] - pred[k];
                pred[k] = v[k];
                int mag = diff < 0 ? -diff : diff, cat = 0;
                while (mag >> cat) ++cat;
                bits.put(dc[static_cast<std::size_t>(cat)].first, dc[static_cast<std::size_t>(cat)].second);
                if (cat > 0) bits.put(static_cast<std::uint32_t>(diff > 0 ? diff : diff + (1 << cat) - 1), cat);
                bits.put(0, 1);  // AC: end of block (the table's one code, "0")
            }
        }
    }
    bits.finish();
    out.insert(out.end(), {0xFF, 0xD9});
    return out;
}

std::vector<std::uint8_t> bmp(const std::vector<std::vector<Rgb>>& blocks, int width, int height) {
    std::size_t stride = (static_cast<std::size_t>(width) * 3 + 3) & ~std::size_t{3};
    std::vector<std::uint8_t> body(stride * static_cast<std::size_t>(height), 0);
    for (int y = 0; y < height; ++y) {
        auto line = pixel_row(blocks[static_cast<std::size_t>(y / BLOCK)], width, false);
        std::uint8_t* dst = body.data() + stride * static_cast<std::size_t>(height - 1 - y);  // bottom-up
        for (int x = 0; x < width; ++x) {  // BGR
            dst[3 * x] = line[3 * static_cast<std::size_t>(x) + 2];
            dst[3 * x + 1] = line[3 * static_cast<std::size_t>(x) + 1];
            dst[3 * x + 2] = line[3 * static_cast<std::size_t>(x)];
        }
    }
    std::vector<std::uint8_t> out{'B', 'M'};
    put32le(out, static_cast<std::uint32_t>(54 + body.size()));
    put32le(out, 0);
    put32le(out, 54);
    put32le(out, 40);
    put32le(out, static_cast<std::uint32_t>(width));
    put32le(out, static_cast<std::uint32_t>(height));
    put16le(out, 1);
    put16le(out, 24);
    put32le(out, 0);
    put32le(out, static_cast<std::uint32_t>(body.size()));
    put32le(out, 2835);
    put32le(out, 2835);
    put32le(out, 0);
    put32le(out, 0);
    out.insert(out.end(), body.begin(), body.end());
    return out;
}

std::vector<std::uint8_t> pnm(const std::vector<std::vector<Rgb>>& blocks, int width, int height, bool grey) {
    std::string head = std::string(grey ? "P5" : "P6") + "\n" + std::to_string(width) + " " + std::to_string(height) +
                       "\n255\n";
    std::vector<std::uint8_t> out(head.begin(), head.end());
    for (int y = 0; y < height; ++y) {
        auto line = pixel_row(blocks[static_cast<std::size_t>(y / BLOCK)], width, grey);
        out.insert(out.end(), line.begin(), line.end());
    }
    return out;
}

std::uint32_t be32(const std::vector<std::uint8_t>& d, std::size_t i) {
    return (std::uint32_t{d[i]} << 24) | (std::uint32_t{d[i + 1]} << 16) | (std::uint32_t{d[i + 2]} << 8) | d[i + 3];
}

}  // namespace

bool can_paint(const std::string& mime) { return kind_of(mime) != Kind::None; }

std::vector<std::uint8_t> synthetic_image(const std::string& mime, int width, int height, double heading,
                                          std::uint32_t frame, bool grey) {
    Kind kind = kind_of(mime);
    if (kind == Kind::None) throw ImageError("no synthetic picture for MIME type '" + mime + "'");
    if (width < 1 || height < 1 || width > 65535 || height > 65535)
        throw ImageError("a picture of " + std::to_string(width) + "x" + std::to_string(height) + " pixels");
    auto blocks = scene((width + BLOCK - 1) / BLOCK, (height + BLOCK - 1) / BLOCK, heading, frame);
    switch (kind) {
        case Kind::Png: return png(blocks, width, height, grey);
        case Kind::Jpeg: return jpeg(blocks, width, height, grey);
        case Kind::Bmp: return bmp(blocks, width, height);
        case Kind::Pgm: return pnm(blocks, width, height, true);
        default: return pnm(blocks, width, height, false);
    }
}

bool describe_image(const std::vector<std::uint8_t>& d, ImageInfo& info) {
    static const std::uint8_t PNG_SIG[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    if (d.size() >= 24 && std::memcmp(d.data(), PNG_SIG, 8) == 0 && std::memcmp(d.data() + 12, "IHDR", 4) == 0) {
        info = {"image/png", static_cast<int>(be32(d, 16)), static_cast<int>(be32(d, 20))};
        return true;
    }
    if (d.size() >= 4 && d[0] == 0xFF && d[1] == 0xD8) {
        std::size_t i = 2;
        while (i + 4 <= d.size()) {
            if (d[i] != 0xFF) return false;
            std::uint8_t m = d[i + 1];
            if (m == 0xFF) {
                ++i;
                continue;
            }
            if (m == 0xD8 || m == 0x01 || (m >= 0xD0 && m <= 0xD7)) {
                i += 2;
                continue;
            }
            std::size_t length = (std::size_t{d[i + 2]} << 8) | d[i + 3];
            bool sof = m >= 0xC0 && m <= 0xCF && m != 0xC4 && m != 0xC8 && m != 0xCC;
            if (sof && i + 9 <= d.size()) {
                info = {"image/jpeg", (d[i + 7] << 8) | d[i + 8], (d[i + 5] << 8) | d[i + 6]};
                return true;
            }
            if (m == 0xDA || m == 0xD9) return false;
            i += 2 + length;
        }
        return false;
    }
    if (d.size() >= 26 && d[0] == 'B' && d[1] == 'M') {
        auto le = [&](std::size_t i) {
            return static_cast<std::int32_t>(std::uint32_t{d[i]} | (std::uint32_t{d[i + 1]} << 8) |
                                             (std::uint32_t{d[i + 2]} << 16) | (std::uint32_t{d[i + 3]} << 24));
        };
        info = {"image/bmp", le(18), std::abs(le(22))};
        return true;
    }
    if (d.size() >= 2 && d[0] == 'P' && (d[1] == '5' || d[1] == '6')) {
        std::string head(d.begin() + 2, d.begin() + static_cast<std::ptrdiff_t>(std::min<std::size_t>(d.size(), 64)));
        int w = 0, h = 0;
        if (std::sscanf(head.c_str(), "%d %d", &w, &h) != 2) return false;
        info = {d[1] == '5' ? "image/x-portable-graymap" : "image/x-portable-pixmap", w, h};
        return true;
    }
    return false;
}

}  // namespace rapid_runtime
