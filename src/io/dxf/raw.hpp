#pragma once
// The DXF content vgd cares about, as read (file units, block coordinates).
// Internal to io/dxf: scan.cpp validates the text, reader.cpp fills these
// structures through dxflib, aama_import.cpp interprets them.
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace vgd::dxf::raw {

struct Vertex {
  double x = 0, y = 0, bulge = 0;
};
struct Polyline {
  std::string layer;
  std::vector<Vertex> vertices;
  bool closed = false;
  int line = 0;
};
struct Point {
  std::string layer;
  double x = 0, y = 0, z = 0;
  double thickness = 0;  // group 39
  double angle = 0;      // group 50, degrees
  bool has_angle = false;
  int line = 0;
};
struct Line {
  std::string layer;
  double x1 = 0, y1 = 0, x2 = 0, y2 = 0;
  int line = 0;
};
struct Text {
  std::string layer;
  double x = 0, y = 0;
  std::string value;
  int line = 0;
};
struct Insert {
  std::string block;
  double x = 0, y = 0, sx = 1, sy = 1, angle_deg = 0;
  int line = 0;
};
struct Block {
  std::string name;
  double base_x = 0, base_y = 0;
  int line = 0;
  std::vector<Polyline> polylines;
  std::vector<Point> points;
  std::vector<Line> lines;
  std::vector<Text> texts;
  std::vector<Insert> inserts;
};
struct Drawing {
  std::vector<Block> blocks;  // in file order, layout blocks excluded
  Block model;                // model-space entities (ENTITIES section)
  std::vector<std::string> comments;             // 999 groups
  std::map<std::string, std::string> header;     // $VARIABLE -> value as text
};

// Validates the text's DXF structure (throws vgd::Error naming the file and line).
struct ScanInfo {
  int lines = 0;
  int pairs = 0;
  int blocks = 0;
  // Line of every "0 / TYPE" pair, per entity type, in file order. dxflib does
  // not report lines when it reads from memory, so the reader takes the n-th
  // entity of a type's line from here.
  std::map<std::string, std::vector<int>, std::less<>> entity_lines;
};
ScanInfo scan(std::string_view text, const std::string& name);

// Reads the validated text through dxflib.
Drawing read(std::string_view text, const std::string& name);

}  // namespace vgd::dxf::raw
