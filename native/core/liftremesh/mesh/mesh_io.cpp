#include "liftremesh/mesh/mesh_io.h"

#include "liftremesh/exceptions.h"
#include "liftremesh/mesh/geometry.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

namespace liftremesh {

namespace {

enum class Format { stl, obj, off };

// ---- messages ---------------------------------------------------------------------------------

std::string quoted(const std::string& path) { return "'" + path + "'"; }

[[noreturn]] void fail(const std::string& path, const std::string& problem) {
    throw InvalidInput(quoted(path) + ": " + problem);
}

[[noreturn]] void fail_at(const std::string& path, long line, const std::string& problem) {
    fail(path, "line " + std::to_string(line) + ": " + problem);
}

// A token of unknown content, made safe for a one-line message: at most 20 printable characters.
std::string printable(std::string_view token) {
    std::string out;
    for (const char c : token.substr(0, 20)) out += std::isprint(static_cast<unsigned char>(c)) ? c : '?';
    if (token.size() > 20) out += "...";
    return out;
}

std::string lowercase(std::string_view s) {
    std::string out(s);
    for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return out;
}

Format format_of(const std::string& path) {
    const std::string ext = lowercase(std::filesystem::path(path).extension().string());
    if (ext == ".stl") return Format::stl;
    if (ext == ".obj") return Format::obj;
    if (ext == ".off") return Format::off;
    if (ext.empty()) fail(path, "no file extension (expected .stl, .obj or .off)");
    fail(path, "unsupported extension '" + printable(ext) + "' (expected .stl, .obj or .off)");
}

// ---- low-level reading ------------------------------------------------------------------------

std::string read_whole_file(const std::string& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) throw InvalidInput("cannot open " + quoted(path) + ": Is a directory");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InvalidInput("cannot open " + quoted(path) + ": " + std::strerror(errno));
    std::string data;
    char buffer[1 << 16];
    while (in.read(buffer, sizeof buffer) || in.gcount() > 0) data.append(buffer, static_cast<size_t>(in.gcount()));
    if (in.bad()) throw InvalidInput("cannot read " + quoted(path) + ": " + std::strerror(errno));
    return data;
}

// Yields the lines of a text buffer one by one (without "\n" or "\r\n"), counting from 1.
class LineReader {
public:
    explicit LineReader(std::string_view data) : data_(data) {}

    bool next(std::string_view& line) {
        if (pos_ >= data_.size()) return false;
        size_t end = data_.find('\n', pos_);
        if (end == std::string_view::npos) end = data_.size();
        line = data_.substr(pos_, end - pos_);
        if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
        pos_ = end + 1;
        ++number_;
        return true;
    }
    long number() const { return number_; }

private:
    std::string_view data_;
    size_t pos_ = 0;
    long number_ = 0;
};

// Splits `line` at blanks (spaces, tabs, other control whitespace).
void split(std::string_view line, std::vector<std::string_view>& tokens) {
    tokens.clear();
    size_t i = 0;
    // What std::isspace takes for a blank in the C locale, without its call per character.
    auto blank = [](char c) { return c == ' ' || (c >= '\t' && c <= '\r'); };
    while (i < line.size()) {
        while (i < line.size() && blank(line[i])) ++i;
        const size_t start = i;
        while (i < line.size() && !blank(line[i])) ++i;
        if (i > start) tokens.push_back(line.substr(start, i - start));
    }
}

// Locale-independent parse of a whole token as a double ("nan" and "inf" accepted: check_mesh
// rejects them later with a clear message). Values out of range become +-inf or 0 as strtod does.
bool parse_double(std::string_view s, double& value) {
    if (!s.empty() && s.front() == '+') s.remove_prefix(1);
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
    if (end != s.data() + s.size()) return false;
    if (ec == std::errc::result_out_of_range) {
        value = std::strtod(std::string(s).c_str(), nullptr);
        return true;
    }
    return ec == std::errc();
}

bool parse_long(std::string_view s, long& value) {
    if (!s.empty() && s.front() == '+') s.remove_prefix(1);
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
    return ec == std::errc() && end == s.data() + s.size();
}

// Reads tokens[first..first+2] as a point.
bool parse_point(const std::vector<std::string_view>& tokens, size_t first, std::array<double, 3>& p) {
    if (tokens.size() < first + 3) return false;
    for (int k = 0; k < 3; ++k)
        if (!parse_double(tokens[first + k], p[k])) return false;
    return true;
}

// ---- triangle soup being read -----------------------------------------------------------------

struct Soup {
    std::vector<std::array<double, 3>> points;
    std::vector<std::array<int32_t, 3>> triangles;

    int32_t add_point(const std::array<double, 3>& p) {
        points.push_back(p);
        return static_cast<int32_t>(points.size() - 1);
    }
    //! Fan triangulation of a polygon with at least 3 corners: (p0, p1, p2), (p0, p2, p3), ...
    void add_polygon(const std::vector<int32_t>& corners) {
        for (size_t k = 1; k + 1 < corners.size(); ++k) triangles.push_back({corners[0], corners[k], corners[k + 1]});
    }
};

Mesh to_mesh(const Soup& soup) {
    Mesh mesh;
    mesh.points.resize(static_cast<Eigen::Index>(soup.points.size()), 3);
    for (size_t i = 0; i < soup.points.size(); ++i)
        for (int k = 0; k < 3; ++k) mesh.points(static_cast<Eigen::Index>(i), k) = soup.points[i][k];
    mesh.triangles.resize(static_cast<Eigen::Index>(soup.triangles.size()), 3);
    for (size_t f = 0; f < soup.triangles.size(); ++f)
        for (int k = 0; k < 3; ++k) mesh.triangles(static_cast<Eigen::Index>(f), k) = soup.triangles[f][k];
    return mesh;
}

// ---- STL ----------------------------------------------------------------------------------------

constexpr size_t kStlHeaderBytes = 84;   // 80-byte header + uint32 triangle count
constexpr size_t kStlTriangleBytes = 50; // normal, 3 corners (12 float32) + uint16 attribute

uint32_t read_u32_le(const char* p) {
    const auto* b = reinterpret_cast<const unsigned char*>(p);
    return static_cast<uint32_t>(b[0]) | static_cast<uint32_t>(b[1]) << 8 | static_cast<uint32_t>(b[2]) << 16 |
           static_cast<uint32_t>(b[3]) << 24;
}

float read_f32_le(const char* p) {
    const uint32_t bits = read_u32_le(p);
    float value;
    std::memcpy(&value, &bits, sizeof value);
    return value;
}

bool starts_with_solid(std::string_view data) {
    size_t i = 0;
    while (i < data.size() && std::isspace(static_cast<unsigned char>(data[i]))) ++i;
    return lowercase(data.substr(i, 5)) == "solid";
}

void parse_stl_binary(const std::string& path, std::string_view data, Soup& soup) {
    const uint64_t n = read_u32_le(data.data() + 80);
    if (3 * n > static_cast<uint64_t>(std::numeric_limits<int32_t>::max()))
        fail(path, "binary STL has " + std::to_string(n) + " triangles (at most 715827882 supported)");
    soup.points.reserve(3 * n);
    soup.triangles.reserve(n);
    for (uint64_t f = 0; f < n; ++f) {
        const char* record = data.data() + kStlHeaderBytes + f * kStlTriangleBytes + 12; // skip the normal
        std::array<int32_t, 3> tri;
        for (int j = 0; j < 3; ++j) {
            std::array<double, 3> p;
            for (int k = 0; k < 3; ++k) p[k] = read_f32_le(record + 4 * (3 * j + k));
            tri[j] = soup.add_point(p);
        }
        soup.triangles.push_back(tri);
    }
}

void parse_stl_ascii(const std::string& path, std::string_view data, Soup& soup) {
    LineReader lines(data);
    std::string_view line;
    std::vector<std::string_view> tokens;
    std::vector<int32_t> loop;
    bool in_loop = false;
    auto close_loop = [&](long line_number) {
        if (loop.size() < 3)
            fail_at(path, line_number, "facet has " + std::to_string(loop.size()) + " vertices (expected 3)");
        soup.add_polygon(loop);
        loop.clear();
        in_loop = false;
    };
    while (lines.next(line)) {
        split(line, tokens);
        if (tokens.empty()) continue;
        const std::string key = lowercase(tokens[0]);
        if (key == "solid" || key == "endsolid" || key == "facet") continue; // names and normals unused
        if (key == "outer") {
            if (in_loop) fail_at(path, lines.number(), "'outer loop' inside a loop (expected 'endloop' first)");
            in_loop = true;
            loop.clear();
        } else if (key == "vertex") {
            std::array<double, 3> p;
            if (tokens.size() != 4 || !parse_point(tokens, 1, p))
                fail_at(path, lines.number(), "expected 3 vertex coordinates");
            if (!in_loop) fail_at(path, lines.number(), "'vertex' outside 'outer loop'");
            loop.push_back(soup.add_point(p));
        } else if (key == "endloop") {
            if (!in_loop) fail_at(path, lines.number(), "'endloop' without 'outer loop'");
            close_loop(lines.number());
        } else if (key == "endfacet") {
            if (in_loop) close_loop(lines.number());
        } else {
            fail_at(path, lines.number(), "unexpected '" + printable(tokens[0]) + "' (expected an ASCII STL keyword)");
        }
    }
    if (in_loop) fail(path, "unexpected end of file inside a facet (expected 'endloop')");
}

// A binary STL may begin with "solid" too: the size 84 + 50 n is the reliable sign, and an ASCII
// STL holds no NUL byte while a binary one nearly always does.
void parse_stl(const std::string& path, std::string_view data, Soup& soup) {
    const uint64_t size = data.size();
    uint64_t expected = 0;
    if (size >= kStlHeaderBytes) {
        expected = kStlHeaderBytes + kStlTriangleBytes * static_cast<uint64_t>(read_u32_le(data.data() + 80));
        if (size == expected) return parse_stl_binary(path, data, soup);
    }
    if (starts_with_solid(data) && data.find('\0') == std::string_view::npos) return parse_stl_ascii(path, data, soup);
    if (size < kStlHeaderBytes)
        fail(path, "binary STL truncated (expected at least 84 bytes, found " + std::to_string(size) + ")");
    if (size < expected)
        fail(path, "binary STL truncated (expected " + std::to_string(expected) + " bytes, found " +
                       std::to_string(size) + ")");
    parse_stl_binary(path, data, soup); // trailing bytes after the last triangle are ignored
}

// ---- OBJ ----------------------------------------------------------------------------------------

void parse_obj(const std::string& path, std::string_view data, Soup& soup) {
    LineReader lines(data);
    std::string_view line;
    std::vector<std::string_view> tokens;
    std::vector<int32_t> corners;
    while (lines.next(line)) {
        split(line, tokens);
        if (tokens.empty()) continue;
        if (tokens[0] == "v") {
            std::array<double, 3> p;
            if (!parse_point(tokens, 1, p)) fail_at(path, lines.number(), "expected 3 vertex coordinates");
            if (soup.points.size() >= static_cast<size_t>(std::numeric_limits<int32_t>::max()))
                fail_at(path, lines.number(), "too many vertices (at most 2147483647 supported)");
            soup.add_point(p);
        } else if (tokens[0] == "f") {
            if (tokens.size() < 4) fail_at(path, lines.number(), "expected at least 3 vertex indices");
            const long n = static_cast<long>(soup.points.size());
            corners.clear();
            for (size_t k = 1; k < tokens.size(); ++k) {
                const std::string_view index_text = tokens[k].substr(0, tokens[k].find('/')); // "i/t/n"
                long index = 0;
                if (!parse_long(index_text, index))
                    fail_at(path, lines.number(), "invalid vertex index '" + printable(tokens[k]) + "'");
                const long resolved = index > 0 ? index - 1 : n + index; // negative: relative to the end
                if (index == 0 || resolved < 0 || resolved >= n)
                    fail_at(path, lines.number(),
                            "vertex index " + std::to_string(index) + " out of range (expected 1 to " +
                                std::to_string(n) + " or -" + std::to_string(n) + " to -1)");
                corners.push_back(static_cast<int32_t>(resolved));
            }
            soup.add_polygon(corners);
        }
        // vn, vt, g, o, s, usemtl, mtllib, l, comments, ...: not geometry we use.
    }
}

// ---- OFF ----------------------------------------------------------------------------------------

// Next line with content, comments ('#' to the end of the line) removed and split into tokens.
bool next_off_line(LineReader& lines, std::vector<std::string_view>& tokens) {
    std::string_view line;
    while (lines.next(line)) {
        split(line.substr(0, line.find('#')), tokens);
        if (!tokens.empty()) return true;
    }
    return false;
}

// Header keyword: [ST][C][N][4][n]OFF. Texture, colour and normal variants only add values after
// the coordinates; 4D, nD and binary files are refused.
void check_off_header(const std::string& path, const std::vector<std::string_view>& tokens, long line) {
    const std::string_view key = tokens[0];
    if (key.size() < 3 || key.substr(key.size() - 3) != "OFF")
        fail_at(path, line, "expected the 'OFF' header, found '" + printable(key) + "'");
    if (key.find('4') != std::string_view::npos || key.find('n') != std::string_view::npos)
        fail_at(path, line, "'" + printable(key) + "' is not a 3D OFF (expected OFF, COFF, NOFF or STOFF)");
    if (tokens.size() > 1 && tokens[1] == "BINARY") fail_at(path, line, "binary OFF is not supported");
}

void parse_off(const std::string& path, std::string_view data, Soup& soup) {
    LineReader lines(data);
    std::vector<std::string_view> tokens;
    if (!next_off_line(lines, tokens)) fail(path, "no content (expected the 'OFF' header)");
    check_off_header(path, tokens, lines.number());
    // The counts may follow the keyword on the same line ("OFF 8 6 12").
    if (tokens.size() == 1 && !next_off_line(lines, tokens)) fail(path, "unexpected end of file (expected counts)");
    const size_t first = tokens[0].size() >= 3 && tokens[0].substr(tokens[0].size() - 3) == "OFF" ? 1 : 0;
    long nv = 0, nf = 0;
    if (tokens.size() < first + 2 || !parse_long(tokens[first], nv) || !parse_long(tokens[first + 1], nf) || nv < 0 ||
        nf < 0)
        fail_at(path, lines.number(), "expected vertex and face counts");
    if (nv > std::numeric_limits<int32_t>::max())
        fail_at(path, lines.number(), "too many vertices (at most 2147483647 supported)");
    // Never trust a header for memory: each vertex needs at least 6 bytes of text.
    soup.points.reserve(std::min<size_t>(static_cast<size_t>(nv), data.size() / 6));
    for (long i = 0; i < nv; ++i) {
        if (!next_off_line(lines, tokens))
            fail(path, "unexpected end of file after " + std::to_string(i) + " of " + std::to_string(nv) + " vertices");
        std::array<double, 3> p;
        if (!parse_point(tokens, 0, p)) fail_at(path, lines.number(), "expected 3 vertex coordinates");
        soup.add_point(p);
    }
    std::vector<int32_t> corners;
    for (long f = 0; f < nf; ++f) {
        if (!next_off_line(lines, tokens))
            fail(path, "unexpected end of file after " + std::to_string(f) + " of " + std::to_string(nf) + " faces");
        long k = 0;
        if (!parse_long(tokens[0], k) || k < 3)
            fail_at(path, lines.number(),
                    "expected a face with at least 3 vertices, found '" + printable(tokens[0]) + "'");
        if (static_cast<long>(tokens.size()) - 1 < k)
            fail_at(path, lines.number(), "expected " + std::to_string(k) + " vertex indices");
        corners.clear();
        for (long j = 1; j <= k; ++j) {
            long index = -1;
            if (!parse_long(tokens[j], index) || index < 0 || index >= nv)
                fail_at(path, lines.number(),
                        "vertex index '" + printable(tokens[j]) + "' out of range (expected 0 to " +
                            std::to_string(nv - 1) + ")");
            corners.push_back(static_cast<int32_t>(index));
        }
        soup.add_polygon(corners);
    }
}

// ---- welding ----------------------------------------------------------------------------------

// Coordinates compared by bit pattern, with -0.0 made +0.0 so that exactly equal values match.
using PointKey = std::array<uint64_t, 3>;

PointKey point_key(const Points& points, Eigen::Index i) {
    PointKey key;
    for (int k = 0; k < 3; ++k) {
        const double x = points(i, k) + 0.0; // -0.0 + 0.0 == +0.0
        std::memcpy(&key[k], &x, sizeof x);
    }
    return key;
}

struct PointKeyHash {
    size_t operator()(const PointKey& key) const {
        uint64_t h = 0x9e3779b97f4a7c15ull;
        for (const uint64_t v : key) { // splitmix64 finaliser per coordinate
            uint64_t z = v + h;
            z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
            z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
            h = z ^ (z >> 31);
        }
        return static_cast<size_t>(h);
    }
};


// ---- writing ----------------------------------------------------------------------------------

void append_number(std::string& out, double value) {
    char buffer[32];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, value); // shortest exact form
    out.append(buffer, result.ptr);
}

void append_integer(std::string& out, long value) {
    char buffer[24];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
    out.append(buffer, result.ptr);
}

void append_u32_le(std::string& out, uint32_t v) {
    for (int k = 0; k < 4; ++k) out += static_cast<char>((v >> (8 * k)) & 0xff);
}

void append_f32_le(std::string& out, double value) {
    const float f = static_cast<float>(value);
    uint32_t bits;
    std::memcpy(&bits, &f, sizeof bits);
    append_u32_le(out, bits);
}

std::string stl_binary_text(const Mesh& mesh) {
    std::string out;
    out.reserve(kStlHeaderBytes + kStlTriangleBytes * mesh.triangles.rows());
    std::string header = "binary STL written by LiftRemesh";
    header.resize(80, ' '); // must not start with "solid"
    out += header;
    append_u32_le(out, static_cast<uint32_t>(mesh.triangles.rows()));
    for (Eigen::Index f = 0; f < mesh.triangles.rows(); ++f) {
        const Eigen::Vector3d a = mesh.points.row(mesh.triangles(f, 0)).transpose();
        const Eigen::Vector3d b = mesh.points.row(mesh.triangles(f, 1)).transpose();
        const Eigen::Vector3d c = mesh.points.row(mesh.triangles(f, 2)).transpose();
        const Eigen::Vector3d n = triangle_normal(a, b, c);
        for (const Eigen::Vector3d* p : {&n, &a, &b, &c})
            for (int k = 0; k < 3; ++k) append_f32_le(out, (*p)[k]);
        out += '\0';
        out += '\0'; // attribute byte count
    }
    return out;
}

void append_vertex_lines(std::string& out, const Points& points, const char* prefix) {
    for (Eigen::Index i = 0; i < points.rows(); ++i) {
        out += prefix;
        for (int k = 0; k < 3; ++k) {
            if (k > 0) out += ' ';
            append_number(out, points(i, k));
        }
        out += '\n';
    }
}

void append_triangle_lines(std::string& out, const Triangles& triangles, const char* prefix, int base) {
    for (Eigen::Index f = 0; f < triangles.rows(); ++f) {
        out += prefix;
        for (int k = 0; k < 3; ++k) {
            if (k > 0) out += ' ';
            append_integer(out, static_cast<long>(triangles(f, k)) + base);
        }
        out += '\n';
    }
}

std::string obj_text(const Mesh& mesh) {
    std::string out = "# written by LiftRemesh\n";
    append_vertex_lines(out, mesh.points, "v ");
    append_triangle_lines(out, mesh.triangles, "f ", 1);
    return out;
}

std::string off_text(const Mesh& mesh) {
    std::string out = "OFF\n";
    append_integer(out, mesh.points.rows());
    out += ' ';
    append_integer(out, mesh.triangles.rows());
    out += " 0\n";
    append_vertex_lines(out, mesh.points, "");
    append_triangle_lines(out, mesh.triangles, "3 ", 0);
    return out;
}

} // namespace

Mesh read_mesh(const std::string& path) {
    format_of(path); // an unsupported name is refused before the file is opened
    return parse_mesh(path, read_whole_file(path));
}

Mesh parse_mesh(const std::string& path, std::string_view data) {
    const Format format = format_of(path);
    if (data.empty()) fail(path, "file is empty (expected a triangle mesh)");
    Soup soup;
    switch (format) {
    case Format::stl: parse_stl(path, data, soup); break;
    case Format::obj: parse_obj(path, data, soup); break;
    case Format::off: parse_off(path, data, soup); break;
    }
    if (soup.triangles.empty()) fail(path, "no triangle found");
    Mesh mesh = to_mesh(soup);
    weld_exact(mesh);
    const auto& t = mesh.triangles;
    if (((t.col(0).array() == t.col(1).array()) || (t.col(1).array() == t.col(2).array()) ||
         (t.col(2).array() == t.col(0).array()))
            .all())
        fail(path,
             "no triangle left after welding (all " + std::to_string(soup.triangles.size()) + " repeat a vertex)");
    return mesh;
}

void check_mesh_extension(const std::string& path) { format_of(path); }

void write_mesh(const std::string& path, const Mesh& mesh) {
    const Format format = format_of(path);
    check_indices(mesh, quoted(path));
    std::string text;
    switch (format) {
    case Format::stl: text = stl_binary_text(mesh); break;
    case Format::obj: text = obj_text(mesh); break;
    case Format::off: text = off_text(mesh); break;
    }
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    if (!out) throw InvalidInput("cannot write " + quoted(path) + ": " + std::strerror(errno));
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    out.close();
    if (!out) throw InvalidInput("cannot write " + quoted(path) + ": " + std::strerror(errno));
}

void weld_exact(Mesh& mesh) {
    check_indices(mesh, "weld_exact");
    const Eigen::Index n = mesh.points.rows();
    // The welded vertices in a table at most half full, by open addressing: each in the first
    // free slot from its key's hash on, where probing from that hash finds it. An STL soup has
    // three points a triangle, for which a map would allocate a node each.
    size_t slots = 16;
    while (slots < 2 * static_cast<size_t>(n)) slots *= 2;
    std::vector<int32_t> table(slots, -1);
    std::vector<PointKey> keys;     // of the welded vertices
    std::vector<Eigen::Index> kept; // representative (first occurrence) of each welded vertex
    std::vector<int32_t> remap(static_cast<size_t>(n));
    const PointKeyHash hash;
    for (Eigen::Index i = 0; i < n; ++i) {
        const PointKey key = point_key(mesh.points, i);
        size_t slot = hash(key) & (slots - 1);
        while (table[slot] >= 0 && keys[table[slot]] != key) slot = (slot + 1) & (slots - 1);
        if (table[slot] < 0) {
            table[slot] = static_cast<int32_t>(kept.size());
            kept.push_back(i);
            keys.push_back(key);
        }
        remap[i] = table[slot];
    }
    Points points(static_cast<Eigen::Index>(kept.size()), 3);
    for (size_t j = 0; j < kept.size(); ++j) points.row(static_cast<Eigen::Index>(j)) = mesh.points.row(kept[j]);

    for (Eigen::Index f = 0; f < mesh.triangles.rows(); ++f)
        for (int j = 0; j < 3; ++j) mesh.triangles(f, j) = remap[mesh.triangles(f, j)];
    mesh.points = std::move(points);
}

} // namespace liftremesh
