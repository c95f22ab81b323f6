#include "Nastran/NastranDeck.h"

#include "Common/IdIndex.h"
#include "Common/Pieces.h"
#include "Common/TextFile.h"
#include "Common/VariantNodes.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <functional>
#include <map>
#include <string_view>
#include <tuple>

namespace fs = std::filesystem;

namespace mlsformats
{
namespace nastran
{
namespace
{
// ---- numbers -----------------------------------------------------------------------------------

// A real in Nastran's forms: parseReal's ("1.", ".5", "1.E3", "1.D3"; an integer too, which Gmsh
// writes in large field) and the exponent without its letter ("1.5-3", "-.5+2": a sign that
// follows a character other than E or D).
bool parseNastranReal(std::string_view field, double& value)
{
  char text[64];
  std::size_t length = 0;
  for (std::size_t i = 0; i < field.size(); ++i)
  {
    const char c = field[i];
    const char before = i > 0 ? field[i - 1] : 'E';
    if (length + 2 > sizeof(text))
    {
      return false;
    }
    if ((c == '+' || c == '-') && before != 'E' && before != 'e' && before != 'D' && before != 'd')
    {
      text[length++] = 'E';
    }
    text[length++] = c;
  }
  return parseReal(text, text + length, value);
}

// A number's significant digits (no trailing zeros) and its decimal exponent: value =
// d.ddd x 10^exponent.
struct Decimal
{
  bool negative = false;
  char digits[24];
  int count = 0;
  int exponent = 0;
};

// Drops the zeros that end number's digits (one digit stays).
void withoutTrailingZeros(Decimal& number)
{
  while (number.count > 1 && number.digits[number.count - 1] == '0')
  {
    --number.count;
  }
}

// value's digits rounded to precision significant ones (0: the fewest that read back as value).
Decimal decimal(double value, int precision)
{
  char text[40];
  const char* end = precision == 0
    ? std::to_chars(text, text + sizeof(text), value, std::chars_format::scientific).ptr
    : std::to_chars(text, text + sizeof(text), value, std::chars_format::scientific, precision - 1).ptr;
  Decimal out;
  out.negative = text[0] == '-';
  const char* e = std::find(static_cast<const char*>(text), end, 'e');
  for (const char* c = text + (out.negative ? 1 : 0); c < e; ++c)
  {
    if (*c != '.')
    {
      out.digits[out.count++] = *c;
    }
  }
  withoutTrailingZeros(out);
  std::from_chars(e + (e[1] == '+' ? 2 : 1), end, out.exponent);
  return out;
}

// value's digits rounded to precision significant ones, from its shortest digits (as many or
// fewer: those): rounding them rounds value, unless they end in a 5 right after the last digit kept
// (their tie may not be value's), which value's own digits round.
Decimal roundedTo(const Decimal& shortest, int precision, double value)
{
  if (precision >= shortest.count)
  {
    return shortest;
  }
  const char next = shortest.digits[precision];
  if (next == '5' && precision + 1 == shortest.count)
  {
    return decimal(value, precision);
  }
  Decimal out = shortest;
  out.count = precision;
  if (next >= '5')
  {
    int i = precision - 1;
    while (i >= 0 && out.digits[i] == '9')
    {
      out.digits[i--] = '0';
    }
    if (i < 0)
    {
      out.digits[0] = '1'; // the nines became the next power of 10
      out.count = 1;
      ++out.exponent;
    }
    else
    {
      ++out.digits[i];
    }
  }
  withoutTrailingZeros(out);
  return out;
}

// A number's Nastran forms, from its digits: without an exponent ("123.4", ".00123", "1200.") or
// with one (".15-99", "1.5-7", "15.+9"). Each has a decimal point, which makes it a real. The
// lengths of the shortest of each (without a sign).
struct FormLengths
{
  int plain, withExponent;
};
// The characters of an exponent's magnitude.
int exponentWidth(int shown)
{
  return shown >= 100 ? 3 : shown >= 10 ? 2 : 1;
}

FormLengths formLengths(int count, int exponent)
{
  // with an exponent: the point at 0..count digits shows exponent + 1 - count .. exponent + 1 (not 0)
  const int low = exponent + 1 - count, high = exponent + 1;
  const int shown = (low <= 1 && 1 <= high) || (low <= -1 && -1 <= high) ? 1 : low > 1 ? low : -high;
  return { exponent >= count - 1 ? exponent + 2 : exponent >= 0 ? count + 1 : count - exponent,
    count + 2 + exponentWidth(shown) };
}

// The length of the shortest form.
int formLength(bool negative, int count, int exponent)
{
  const FormLengths lengths = formLengths(count, exponent);
  return (negative ? 1 : 0) + std::min(lengths.plain, lengths.withExponent);
}

// Where the point of the shortest form is among the digits when it has an exponent, else -1 (no
// exponent when that is as short): right after the first digit, else before it, else the first
// place further right.
int formPoint(int count, int exponent)
{
  const FormLengths lengths = formLengths(count, exponent);
  for (int place = 0; place <= count && lengths.withExponent < lengths.plain; ++place)
  {
    const int at = place == 0 ? 1 : place == 1 ? 0 : place;
    const int shown = std::abs(exponent + 1 - at);
    if (shown != 0 && count + 2 + exponentWidth(shown) == lengths.withExponent)
    {
      return at;
    }
  }
  return -1;
}

std::string formText(const Decimal& number)
{
  const int point = formPoint(number.count, number.exponent);
  const std::string_view digits(number.digits, static_cast<std::size_t>(number.count));
  const int count = number.count, exponent = number.exponent;
  std::string out = number.negative ? "-" : "";
  if (point >= 0)
  {
    const int shown = exponent + 1 - point;
    out.append(digits.substr(0, point)).append(".").append(digits.substr(point));
    out.append(shown > 0 ? "+" : "-").append(std::to_string(std::abs(shown)));
  }
  else if (exponent >= count - 1)
  {
    out.append(digits).append(exponent - count + 1, '0').append(".");
  }
  else if (exponent >= 0)
  {
    out.append(digits.substr(0, exponent + 1)).append(".").append(digits.substr(exponent + 1));
  }
  else
  {
    out.append(".").append(-exponent - 1, '0').append(digits);
  }
  return out;
}

// The text of value in at most width characters: the shortest that reads back as value, else the
// closest of as many significant digits as fit ("1.2346-5" in a small field's 8 characters).
std::string nastranReal(double value, std::size_t width)
{
  if (value == 0)
  {
    return "0.";
  }
  const Decimal shortest = decimal(value, 0);
  const int fits = static_cast<int>(width);
  if (formLength(shortest.negative, shortest.count, shortest.exponent) <= fits)
  {
    return formText(shortest);
  }
  // the most digits whose form at this exponent fits: the text of any more digits that fits is
  // theirs (its further digits are zeros) or it rounds up to the next power of 10 (as they do);
  // then fewer, while rounding changes the exponent (a form of n digits takes n + 1 characters)
  int precision = std::min(17, fits - 1);
  while (precision > 1 && formLength(shortest.negative, precision, shortest.exponent) > fits)
  {
    --precision;
  }
  Decimal rounded = roundedTo(shortest, precision, value);
  while (formLength(rounded.negative, rounded.count, rounded.exponent) > fits && precision > 1)
  {
    rounded = roundedTo(shortest, --precision, value);
  }
  return formText(rounded);
}

// ---- entries: their lines and fields -----------------------------------------------------------

std::string upperCase(std::string_view text)
{
  std::string out(text);
  for (char& c : out)
  {
    c = c >= 'a' && c <= 'z' ? static_cast<char>(c - 'a' + 'A') : c; // ASCII, whatever the locale
  }
  return out;
}

// A line from begin: where it ends (without "\r") and where the next starts.
Line lineAt(std::string_view text, std::size_t begin)
{
  std::size_t end = text.find('\n', begin);
  const std::size_t next = end == std::string::npos ? text.size() : end + 1;
  end = end == std::string::npos ? text.size() : end;
  return { begin, end > begin && text[end - 1] == '\r' ? end - 1 : end, next };
}

// Blank, or only a comment.
bool isComment(std::string_view line)
{
  const std::size_t first = line.find_first_not_of(" \t");
  return first == std::string_view::npos || line[first] == '$';
}

// A continuation line starts with "+", "*", "," or a blank.
bool continues(std::string_view line)
{
  return line[0] == '+' || line[0] == '*' || line[0] == ',' || isBlank(line[0]);
}

// The letters and digits at a line's start, in upper case ("GRID", "INCLUDE", "BEGIN").
std::string leadingWord(std::string_view line)
{
  std::size_t end = 0;
  while (end < line.size() && std::isalnum(static_cast<unsigned char>(line[end])))
  {
    ++end;
  }
  return upperCase(line.substr(0, end));
}

// Whether the words after BEGIN are BULK alone (not BEGIN SUPER=2, BEGIN BULK AUXMODEL=1).
bool beginsBulk(std::string_view line)
{
  std::string_view rest = line.substr(5, line.find('$') == std::string_view::npos ? std::string_view::npos : line.find('$') - 5);
  rest = trim(rest);
  while (!rest.empty() && rest.front() == ',')
  {
    rest = trim(rest.substr(1));
  }
  return upperCase(rest) == "BULK";
}

// One line of an entry.
struct EntryLine
{
  std::size_t begin, end; // in the file's text
  std::size_t number;     // in the file, from 1
  bool free, large;       // commas; 16-column fields (or 4 a line in free field)
  std::string expanded;   // a fixed-field line with tabs: its content with the tabs expanded
  std::string_view content; // before any "$" comment (expanded, if it is)
};

// One of an entry's data fields.
struct Field
{
  std::string_view text; // without the blanks around it
  std::uint32_t line;    // in Entry::lines
  std::uint32_t begin, end; // fixed field: its columns in the line's content; free field: its text's
  std::uint32_t commas;  // free field after the line's last: the commas to add before it
};

// An entry (a "card"): its name and its data fields, those of each line (2-9; large field 2-5,
// each line half of a small field's), blank ones too.
struct Entry
{
  std::string name; // upper case, without "*"
  std::vector<EntryLine> lines;
  std::vector<Field> fields;
  std::size_t next = 0; // where the line after its last starts
  std::size_t lineCount = 0; // its lines, the comments between them included
};

std::string expandTabs(std::string_view text)
{
  std::string out;
  for (const char c : text)
  {
    if (c == '\t')
    {
      out.append(8 - out.size() % 8, ' ');
    }
    else
    {
      out.push_back(c);
    }
  }
  return out;
}

// Appends the data fields of line l.
void splitLine(Entry& entry, std::uint32_t l, const std::string& file)
{
  const EntryLine& line = entry.lines[l];
  const std::string_view content = line.content;
  const std::uint32_t perLine = line.large ? 4 : 8;
  if (!line.free)
  {
    const std::uint32_t width = line.large ? 16 : 8;
    for (std::uint32_t k = 0; k < perLine; ++k)
    {
      const std::uint32_t begin = 8 + k * width;
      const std::string_view text = begin < content.size() ? trim(content.substr(begin, width)) : std::string_view();
      entry.fields.push_back({ text, l, begin, begin + width, 0 });
    }
    return;
  }
  // between the commas: the name or continuation mark, the data, the next line's mark
  std::size_t comma = content.find(',');
  std::uint32_t k = 0;
  for (; k < perLine && comma != std::string_view::npos; ++k)
  {
    const std::size_t begin = comma + 1;
    comma = content.find(',', begin);
    const std::string_view text = trim(content.substr(begin, comma == std::string_view::npos ? std::string_view::npos : comma - begin));
    const std::size_t at = text.empty() ? begin : static_cast<std::size_t>(text.data() - content.data());
    entry.fields.push_back({ text, l, static_cast<std::uint32_t>(at), static_cast<std::uint32_t>(at + text.size()), 0 });
  }
  const std::string_view used = trim(content);
  const std::uint32_t last = static_cast<std::uint32_t>(used.data() + used.size() - content.data());
  for (std::uint32_t missing = 1; k < perLine; ++k, ++missing)
  {
    entry.fields.push_back({ std::string_view(), l, last, last, missing });
  }
  // after the data, the next line's mark alone (and blank fields)
  const std::size_t extra = comma == std::string_view::npos ? comma : content.find(',', comma + 1);
  if (extra != std::string_view::npos && content.find_first_not_of(", \t", extra) != std::string_view::npos)
  {
    throw FileError(file, line.number, "more than " + std::to_string(perLine) + " data fields on a free-field line");
  }
}

// Reads the entry whose first line starts at begin (line number there): that line and its
// continuation lines, comment lines between them skipped.
void readEntry(std::string_view text, std::size_t begin, std::size_t number, const std::string& file, Entry& entry)
{
  entry.lines.clear();
  entry.fields.clear();
  std::size_t at = begin, skipped = 0;
  while (at < text.size())
  {
    const Line span = lineAt(text, at);
    const std::string_view line(text.data() + at, span.end - at);
    if (!entry.lines.empty() && isComment(line))
    {
      ++skipped;
      at = span.next;
      continue;
    }
    if (!entry.lines.empty() && !continues(line))
    {
      break;
    }
    number += entry.lines.empty() ? 0 : skipped + 1;
    skipped = 0;
    EntryLine added{ at, span.end, number, false, false, {}, {} };
    const std::string_view content = line.substr(0, line.find('$'));
    added.free = content.find(',') != std::string_view::npos;
    if (!added.free && content.find('\t') != std::string_view::npos)
    {
      added.expanded = expandTabs(content);
    }
    const std::string_view fixed = added.expanded.empty() ? content : std::string_view(added.expanded);
    const std::string_view mark = trim(added.free ? content.substr(0, content.find(',')) : fixed.substr(0, 8));
    added.large = entry.lines.empty() ? !mark.empty() && mark.back() == '*' : !mark.empty() && mark.front() == '*';
    if (entry.lines.empty())
    {
      entry.name = upperCase(mark.substr(0, mark.size() - (added.large ? 1 : 0)));
    }
    entry.lines.push_back(std::move(added));
    at = span.next;
  }
  entry.next = lineAt(text, entry.lines.back().begin).next;
  entry.lineCount = number - entry.lines.front().number + 1;
  for (std::uint32_t l = 0; l < entry.lines.size(); ++l)
  {
    EntryLine& line = entry.lines[l];
    const std::string_view whole(text.data() + line.begin, line.end - line.begin);
    line.content = line.expanded.empty() ? whole.substr(0, whole.find('$')) : std::string_view(line.expanded);
    splitLine(entry, l, file);
  }
}

// ---- coordinate systems ------------------------------------------------------------------------

constexpr double Degree = 3.14159265358979323846 / 180;

// A point's X1 X2 X3 in system to its basic coordinates, in place.
void toBasic(const CoordinateSystem& system, double* x)
{
  double r[3] = { x[0], x[1], x[2] };
  if (system.type == 'C')
  {
    r[0] = x[0] * std::cos(x[1] * Degree);
    r[1] = x[0] * std::sin(x[1] * Degree);
  }
  else if (system.type == 'S')
  {
    r[0] = x[0] * std::sin(x[1] * Degree) * std::cos(x[2] * Degree);
    r[1] = x[0] * std::sin(x[1] * Degree) * std::sin(x[2] * Degree);
    r[2] = x[0] * std::cos(x[1] * Degree);
  }
  for (int c = 0; c < 3; ++c)
  {
    x[c] = system.origin[c] + r[0] * system.axes[0][c] + r[1] * system.axes[1][c] + r[2] * system.axes[2][c];
  }
}

// A point's basic coordinates to its X1 X2 X3 in system, in place; old: its X1 X2 X3 before it
// moved, whose angles it keeps where any would do (on the axis). An azimuth is in (-180, 180], or in
// [0, 360) when old's was not negative.
void toLocal(const CoordinateSystem& system, double* x, const double* old)
{
  double r[3];
  for (int a = 0; a < 3; ++a)
  {
    r[a] = (x[0] - system.origin[0]) * system.axes[a][0] + (x[1] - system.origin[1]) * system.axes[a][1] +
      (x[2] - system.origin[2]) * system.axes[a][2];
  }
  const double planar = std::hypot(r[0], r[1]);
  const int azimuth = system.type == 'S' ? 2 : 1;
  double angle = planar > 0 ? std::atan2(r[1], r[0]) / Degree : old[azimuth];
  angle += angle < 0 && old[azimuth] >= 0 ? 360 : 0;
  if (system.type == 'R')
  {
    std::copy(r, r + 3, x);
  }
  else if (system.type == 'C')
  {
    x[0] = planar;
    x[1] = angle;
    x[2] = r[2];
  }
  else
  {
    x[0] = std::hypot(planar, r[2]);
    x[1] = x[0] > 0 ? std::atan2(planar, r[2]) / Degree : old[1];
    x[2] = angle;
  }
}

// ---- elements ----------------------------------------------------------------------------------

// An element entry that becomes a cell.
struct ElementCard
{
  const char* name;
  bool property;      // its field 3 is a PID (CONROD's is its first grid)
  int corners, edges; // its grids: the corners, then the edge grids (a cell has all or none)
  CellType linear, quadratic;
  std::vector<int> order; // with its edge grids: VTK's node i is the entry's grid order[i] (empty: the same)
};

// The QRG's grid numbers: CTETRA's G5-G10 on the edges 1-2 2-3 3-1 1-4 2-4 3-4, CPYRAM's G6-G13
// on 1-2 2-3 3-4 4-1 1-5 2-5 3-5 4-5, CTRIA6's and CQUAD8's around the face: VTK's. CPENTA's
// G7-G15 on the edges of 1-2-3, then 1-4 2-5 3-6, then those of 4-5-6; CHEXA's G9-G20 on the edges
// of 1-2-3-4, then 1-5 2-6 3-7 4-8, then those of 5-6-7-8 (as Gmsh's getVertexBDF and its BDF
// reader, pyNastran's and meshio's number them): VTK's have the top face's before the vertical ones.
const ElementCard* elementCard(const std::string& name)
{
  static const std::vector<ElementCard> cards = {
    { "CTETRA", true, 4, 6, CellType::Tetra, CellType::QuadraticTetra, {} },
    { "CPYRAM", true, 5, 8, CellType::Pyramid, CellType::QuadraticPyramid, {} },
    { "CPENTA", true, 6, 9, CellType::Wedge, CellType::QuadraticWedge, { 0, 1, 2, 3, 4, 5, 6, 7, 8, 12, 13, 14, 9, 10, 11 } },
    { "CHEXA", true, 8, 12, CellType::Hexahedron, CellType::QuadraticHexahedron,
      { 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 16, 17, 18, 19, 12, 13, 14, 15 } },
    { "CTRIA3", true, 3, 0, CellType::Triangle, CellType::Triangle, {} },
    { "CTRIAR", true, 3, 0, CellType::Triangle, CellType::Triangle, {} },
    { "CTRIA6", true, 3, 3, CellType::Triangle, CellType::QuadraticTriangle, {} },
    { "CQUAD4", true, 4, 0, CellType::Quad, CellType::Quad, {} },
    { "CQUADR", true, 4, 0, CellType::Quad, CellType::Quad, {} },
    { "CSHEAR", true, 4, 0, CellType::Quad, CellType::Quad, {} },
    { "CQUAD8", true, 4, 4, CellType::Quad, CellType::QuadraticQuad, {} },
    { "CBAR", true, 2, 0, CellType::Line, CellType::Line, {} },
    { "CBEAM", true, 2, 0, CellType::Line, CellType::Line, {} },
    { "CROD", true, 2, 0, CellType::Line, CellType::Line, {} },
    { "CTUBE", true, 2, 0, CellType::Line, CellType::Line, {} },
    { "CONROD", false, 2, 0, CellType::Line, CellType::Line, {} },
  };
  for (const ElementCard& card : cards)
  {
    if (name == card.name)
    {
      return &card;
    }
  }
  return nullptr;
}

// The element entries left out with a warning (masses, springs and dampers silently).
bool isOtherElement(const std::string& name)
{
  static const char* const names[] = { "CAXISYM", "CBEAM3", "CBEND", "CBUSH", "CBUSH1D", "CBUSH2D", "CCONEAX", "CFAST", "CGAP",
    "CHBDYE", "CHBDYG", "CHBDYP", "CQUAD", "CQUADX", "CSEAM", "CTRAX3", "CTRAX6", "CTRIAX", "CTRIAX6", "CVISC", "CWELD", "PLOTEL",
    "RBAR", "RBAR1", "RBE1", "RROD", "RSPLINE", "RTRPLT" };
  return std::find(std::begin(names), std::end(names), name) != std::end(names);
}

// A solid's corners, and whether its base face turns away from the rest (VTK 9.2's wedge: (0, 1, 2)
// turns away from (3, 4, 5); its tetrahedron, pyramid and hexahedron turn their base towards the
// rest). 0 corners: not a solid.
int solidCorners(CellType type, bool& away)
{
  away = type == CellType::Wedge || type == CellType::QuadraticWedge;
  switch (type)
  {
    case CellType::Tetra:
    case CellType::QuadraticTetra: return 4;
    case CellType::Pyramid:
    case CellType::QuadraticPyramid: return 5;
    case CellType::Wedge:
    case CellType::QuadraticWedge: return 6;
    case CellType::Hexahedron:
    case CellType::QuadraticHexahedron: return 8;
    default: return 0;
  }
}

// The solid turned inside out, in VTK's order: its base face's corners reversed, and the edges.
const std::vector<int>& mirrored(CellType type)
{
  static const std::vector<int> none, tetra = { 0, 2, 1, 3 }, quadraticTetra = { 0, 2, 1, 3, 6, 5, 4, 7, 9, 8 },
                                      pyramid = { 0, 3, 2, 1, 4 }, quadraticPyramid = { 0, 3, 2, 1, 4, 8, 7, 6, 5, 9, 12, 11, 10 },
                                      wedge = { 0, 2, 1, 3, 5, 4 }, quadraticWedge = { 0, 2, 1, 3, 5, 4, 8, 7, 6, 11, 10, 9, 12, 14, 13 },
                                      hexahedron = { 0, 3, 2, 1, 4, 7, 6, 5 },
                                      quadraticHexahedron = { 0, 3, 2, 1, 4, 7, 6, 5, 11, 10, 9, 8, 15, 14, 13, 12, 16, 19, 18, 17 };
  switch (type)
  {
    case CellType::Tetra: return tetra;
    case CellType::QuadraticTetra: return quadraticTetra;
    case CellType::Pyramid: return pyramid;
    case CellType::QuadraticPyramid: return quadraticPyramid;
    case CellType::Wedge: return wedge;
    case CellType::QuadraticWedge: return quadraticWedge;
    case CellType::Hexahedron: return hexahedron;
    case CellType::QuadraticHexahedron: return quadraticHexahedron;
    default: return none;
  }
}

// ---- the reader --------------------------------------------------------------------------------

// A coordinate system as the deck defines it, resolved once every grid is read.
struct SystemDefinition
{
  std::string card;            // "CORD2C"
  std::int64_t reference = 0;  // CORD2: RID
  double points[9] = {};       // CORD2: A, B and C in the reference system
  std::int64_t grids[3] = {};  // CORD1: the grids at A, B and C
  std::uint32_t file = 0;
  std::size_t line = 0;
  int state = 0;               // 1 resolving, 2 resolved (into Deck::systems[index])
  std::uint32_t index = 0;
};

// An element's or a set item's place: its file (high 24 bits) and line.
constexpr std::uint64_t LineBits = (std::uint64_t(1) << 40) - 1;

// The names of an element's grid fields.
const char* const GridNames[] = { "G1", "G2", "G3", "G4", "G5", "G6", "G7", "G8", "G9", "G10", "G11", "G12", "G13", "G14", "G15",
  "G16", "G17", "G18", "G19", "G20" };

// The grids of a node set as listed: an id, or the ids first THRU last that exist.
struct SetItem
{
  std::int64_t first, last;
  bool range;
  std::uint64_t where;
};

struct NodeSetDefinition
{
  std::string name;
  std::vector<SetItem> items;
};

class Reader
{
public:
  Reader(const std::string& path, bool layoutOnly)
    : LayoutOnly(layoutOnly)
    , Folder(fs::path(path).parent_path())
  {
    this->Out.systems.emplace_back(); // basic
    this->read(path, "", 0);
    this->placeGrids();
    if (layoutOnly)
    {
      this->Out.mesh.xyz = {};
      return;
    }
    this->checkElements();
    this->resolveNodeSets();
    for (const auto& [name, note] : this->Others)
    {
      const std::string count = note.second > 1 ? " (" + std::to_string(note.second) + " entries, the first here)" : "";
      this->Out.mesh.warnings.push_back(
        note.first + ": " + name + count + " is not read as cells: its grids are read and move with the mesh");
    }
  }

  Deck Out;

private:
  bool LayoutOnly;
  fs::path Folder;
  bool Control = false; // in the executive and case control statements, before BEGIN BULK
  bool Ended = false;   // after ENDDATA
  std::uint32_t File = 0;
  std::size_t Line = 0;
  Entry Current;
  std::vector<std::int64_t> Grid; // an element's grids

  std::vector<std::int64_t> GridSystems; // a grid's CP as written (-1: blank)
  std::int64_t DefaultSystem = 0;       // GRDSET's CP
  std::map<std::int64_t, SystemDefinition> Definitions;
  std::vector<char> Placed; // a grid's coordinates: 1 being made basic, 2 basic
  IdIndex Grids{ std::vector<std::int64_t>() };

  std::map<std::pair<std::string, CellType>, std::size_t> Blocks;
  std::vector<std::vector<std::uint64_t>> Where; // each element's place
  std::map<std::int64_t, std::size_t> Properties; // a PID's element set
  std::vector<NodeSetDefinition> NodeSets;
  std::map<std::string, std::pair<std::string, std::size_t>> Others; // an entry left out: its first place and count

  [[noreturn]] void fail(const std::string& reason) const
  {
    throw FileError(this->Out.files[this->File], this->Line, reason);
  }

  std::uint64_t here() const
  {
    return static_cast<std::uint64_t>(this->File) << 40 | this->Line;
  }

  [[noreturn]] void failAt(std::uint64_t where, const std::string& reason) const
  {
    throw FileError(this->Out.files[where >> 40], where & LineBits, reason);
  }

  void read(const std::string& path, const std::string& includeName, int depth)
  {
    if (depth > 20)
    {
      this->fail("INCLUDE nested more than 20 deep (does a file include itself?)");
    }
    const std::string text = readFile(path);
    const std::uint32_t file = static_cast<std::uint32_t>(this->Out.files.size());
    this->Out.files.push_back(path);
    this->Out.hashes.push_back(contentHash(text));
    this->Out.gridsEnd.push_back(0);
    this->Out.includeNames.push_back(includeName);
    const std::uint32_t includingFile = this->File;
    const std::size_t includingLine = this->Line;
    this->File = file;
    this->Line = 0;
    if (depth == 0)
    {
      this->Control = hasControl(text);
    }
    std::size_t begin = 0;
    while (begin < text.size() && !this->Ended)
    {
      const mlsformats::Line span = lineAt(text, begin);
      ++this->Line;
      const std::string_view line(text.data() + begin, span.end - begin);
      const bool comment = isComment(line);
      const std::string word = comment ? std::string() : leadingWord(line);
      if (word == "INCLUDE")
      {
        begin = this->include(text, span, depth);
        continue;
      }
      if (word == "ENDDATA")
      {
        this->Ended = true;
      }
      else if (word == "BEGIN")
      {
        if (!beginsBulk(line))
        {
          this->fail(std::string(trim(line)) + ": part superelements and auxiliary models are not supported");
        }
        this->Control = false;
      }
      else if (!comment && !this->Control)
      {
        if (continues(line))
        {
          this->fail("a continuation line with no entry before it (an entry continued across an INCLUDE is not supported)");
        }
        readEntry(text, begin, this->Line, path, this->Current);
        this->entry(begin);
        this->Line += this->Current.lineCount - 1;
        begin = this->Current.next;
        continue;
      }
      begin = span.next;
    }
    this->File = includingFile;
    this->Line = includingLine;
  }

  // Whether a deck starts with executive and case control statements: it has CEND or BEGIN BULK.
  static bool hasControl(const std::string& text)
  {
    for (std::size_t begin = 0; begin < text.size();)
    {
      const mlsformats::Line span = lineAt(text, begin);
      const std::string_view line(text.data() + begin, span.end - begin);
      const std::string word = leadingWord(line);
      if (word == "CEND" || (word == "BEGIN" && beginsBulk(line)))
      {
        return true;
      }
      begin = span.next;
    }
    return false;
  }

  // INCLUDE 'name' (a quoted name may continue on the next lines) or INCLUDE name: reads the file
  // and returns where the line after the statement starts.
  std::size_t include(const std::string& text, mlsformats::Line span, int depth)
  {
    std::string_view rest = trim(std::string_view(text.data() + span.begin, span.end - span.begin).substr(7));
    std::string name;
    if (!rest.empty() && rest[0] == '\'')
    {
      name = std::string(rest.substr(1));
      while (name.find('\'') == std::string::npos)
      {
        if (span.next >= text.size())
        {
          this->fail("INCLUDE's file name has no closing quote");
        }
        span = lineAt(text, span.next);
        ++this->Line;
        name += trim(std::string_view(text.data() + span.begin, span.end - span.begin));
      }
      name.resize(name.find('\''));
    }
    else
    {
      name = std::string(rest.substr(0, std::min(rest.find_first_of(" \t$"), rest.size())));
    }
    if (name.empty())
    {
      this->fail("INCLUDE without a file name");
    }
    const fs::path included = fs::path(name).is_absolute() ? fs::path(name) : this->Folder / name;
    if (!fs::exists(included))
    {
      this->fail("INCLUDE '" + name + "': " + included.string() + " does not exist");
    }
    this->read(included.string(), name, depth + 1);
    return span.next;
  }

  // ---- fields ----

  std::string_view field(std::size_t i) const
  {
    return i < this->Current.fields.size() ? this->Current.fields[i].text : std::string_view();
  }

  [[noreturn]] void failField(std::size_t i, const std::string& reason) const
  {
    const Entry& entry = this->Current;
    throw FileError(this->Out.files[this->File], entry.lines[i < entry.fields.size() ? entry.fields[i].line : 0].number, reason);
  }

  // The words an error names field i by: "GRID 12's X1", "GRID's id".
  std::string fieldName(std::int64_t owner, const char* what) const
  {
    return this->Current.name + (owner > 0 ? " " + std::to_string(owner) + "'s " : "'s ") + what;
  }

  // Field i's integer (> 0, or >= 0 with zero set), or blank's value when it is blank; owner: the
  // entry's id (0: none yet).
  std::int64_t integer(std::size_t i, std::int64_t owner, const char* what, std::int64_t blank = -1, bool zero = false) const
  {
    const std::string_view text = this->field(i);
    std::int64_t value = 0;
    if (text.empty() && blank >= 0)
    {
      return blank;
    }
    if (!parseInteger(text.data(), text.data() + text.size(), value) || value < (zero ? 0 : 1))
    {
      this->failField(i, this->fieldName(owner, what) + (text.empty() ? " is blank" : " \"" + std::string(text) + "\" is not " +
        (zero ? "an integer >= 0" : "a positive integer")));
    }
    return value;
  }

  // Field i's real (blank: 0).
  double real(std::size_t i, std::int64_t owner, const char* what) const
  {
    const std::string_view text = this->field(i);
    double value = 0;
    if (!text.empty() && !parseNastranReal(text, value))
    {
      this->failField(i, this->fieldName(owner, what) + " \"" + std::string(text) + "\" is not a finite number");
    }
    return value;
  }

  // ---- entries ----

  void entry(std::size_t begin)
  {
    const std::string& name = this->Current.name;
    if (name == "GRID")
    {
      this->grid(begin);
    }
    else if (name == "GRDSET")
    {
      this->DefaultSystem = this->integer(1, 0, "CP", 0, true);
    }
    else if (name.compare(0, 4, "CORD") == 0)
    {
      this->coordinateSystem();
    }
    else if (this->LayoutOnly)
    {
      return;
    }
    else if (const ElementCard* card = elementCard(name))
    {
      this->element(*card);
    }
    else if (name == "RBE2" || name == "RBE3")
    {
      this->rigid();
    }
    else if (name == "SPC1")
    {
      this->constraint();
    }
    else if (isOtherElement(name))
    {
      this->other(name);
    }
  }

  void other(const std::string& what)
  {
    auto& [where, count] = this->Others[what];
    where = count++ == 0 ? this->Out.files[this->File] + ":" + std::to_string(this->Line) : where;
  }

  void grid(std::size_t begin)
  {
    const std::int64_t id = this->integer(0, 0, "id");
    if (this->Current.fields.size() < 5)
    {
      this->fail("GRID* " + std::to_string(id) + " has no continuation line (its X3)");
    }
    this->GridSystems.push_back(this->field(1).empty() ? -1 : this->integer(1, id, "CP", 0, true));
    this->Out.mesh.nodeIds.push_back(id);
    this->Out.slots.push_back({ this->File, 0, begin });
    this->Out.gridsEnd[this->File] = this->Current.next;
    static const char* const names[] = { "X1", "X2", "X3" };
    for (int c = 0; c < 3; ++c)
    {
      this->Out.mesh.xyz.push_back(this->real(2 + c, id, names[c]));
    }
  }

  void coordinateSystem()
  {
    const std::string& name = this->Current.name;
    const bool form1 = name == "CORD1R" || name == "CORD1C" || name == "CORD1S";
    const bool form2 = name == "CORD2R" || name == "CORD2C" || name == "CORD2S";
    // CORD1 defines one or two systems; others (CORD3G...) are refused where a grid is in them
    for (std::size_t first = 0; first == 0 || (form1 && first == 4 && !this->field(4).empty()); first += 4)
    {
      SystemDefinition definition;
      definition.card = name;
      definition.file = this->File;
      definition.line = this->Line;
      const std::int64_t id = this->integer(first, 0, "CID");
      for (int g = 0; form1 && g < 3; ++g)
      {
        definition.grids[g] = this->integer(first + 1 + g, id, GridNames[g]);
      }
      if (form2)
      {
        definition.reference = this->integer(1, id, "RID", 0, true);
        static const char* const names[] = { "A1", "A2", "A3", "B1", "B2", "B3", "C1", "C2", "C3" };
        for (int p = 0; p < 9; ++p)
        {
          definition.points[p] = this->real(2 + p, id, names[p]);
        }
      }
      const auto [found, added] = this->Definitions.emplace(id, definition);
      if (!added)
      {
        this->fail("coordinate system " + std::to_string(id) + " is defined twice (first by the " + found->second.card + " at " +
          this->Out.files[found->second.file] + ":" + std::to_string(found->second.line) + ")");
      }
    }
  }

  void element(const ElementCard& card)
  {
    const std::int64_t id = this->integer(0, 0, "id");
    const std::size_t first = card.property ? 2 : 1;
    std::vector<std::int64_t>& grids = this->Grid;
    grids.clear();
    for (int g = 0; g < card.corners; ++g)
    {
      grids.push_back(this->integer(first + g, id, GridNames[g]));
    }
    int edges = 0;
    for (int g = card.corners; g < card.corners + card.edges; ++g)
    {
      const std::string_view text = this->field(first + g);
      if (!text.empty() && text != "0")
      {
        grids.push_back(this->integer(first + g, id, GridNames[g]));
        ++edges;
      }
    }
    if (edges != 0 && edges != card.edges)
    {
      this->other(std::string(card.name) + " with some of its edge grids");
      return;
    }
    const CellType type = edges != 0 ? card.quadratic : card.linear;
    const auto [found, added] = this->Blocks.emplace(std::make_pair(std::string(card.name), type), this->Out.mesh.blocks.size());
    if (added)
    {
      this->Out.mesh.blocks.push_back({ card.name, type, {}, {} });
      this->Where.emplace_back();
    }
    ElementBlock& block = this->Out.mesh.blocks[found->second];
    block.ids.push_back(id);
    for (std::size_t i = 0; i < grids.size(); ++i)
    {
      block.nodes.push_back(grids[edges != 0 && !card.order.empty() ? card.order[i] : i]);
    }
    this->Where[found->second].push_back(this->here());
    if (card.property)
    {
      const std::int64_t property = this->integer(1, id, "PID", id);
      const auto [set, first] = this->Properties.emplace(property, this->Out.mesh.elementSets.size());
      if (first)
      {
        this->Out.mesh.elementSets.push_back({ "PID " + std::to_string(property), {} });
      }
      this->Out.mesh.elementSets[set->second].ids.push_back(id);
    }
  }

  NodeSetDefinition& nodeSet(const std::string& name)
  {
    for (NodeSetDefinition& set : this->NodeSets)
    {
      if (set.name == name)
      {
        return set;
      }
    }
    this->NodeSets.push_back({ name, {} });
    return this->NodeSets.back();
  }

  void addGrid(NodeSetDefinition& set, std::size_t i, std::int64_t owner)
  {
    const std::int64_t id = this->integer(i, owner, "grid");
    set.items.push_back({ id, id, false, this->here() });
  }

  // RBE2 EID GN CM GM1 GM2 ... [ALPHA]; RBE3 EID blank REFGRID REFC WT1 C1 G1,1 G1,2 ... WT2 C2 ...
  // [UM GM1 CM1 ...] [ALPHA ...]: their grids, in set "RBE2" or "RBE3".
  void rigid()
  {
    const bool rbe2 = this->Current.name == "RBE2";
    NodeSetDefinition& set = this->nodeSet(this->Current.name);
    const std::int64_t id = this->integer(0, 0, "id");
    this->addGrid(set, rbe2 ? 1 : 2, id);
    bool dependent = false, component = false;
    for (std::size_t i = rbe2 ? 3 : 4; i < this->Current.fields.size(); ++i)
    {
      const std::string_view text = this->field(i);
      if (text.empty())
      {
        continue;
      }
      std::int64_t value = 0;
      const bool number = parseInteger(text.data(), text.data() + text.size(), value);
      if (!rbe2 && upperCase(text) == "UM")
      {
        dependent = true; // pairs of a grid and its components
        component = false;
      }
      else if (!number)
      {
        if (rbe2 || dependent || std::isalpha(static_cast<unsigned char>(text[0])))
        {
          break; // ALPHA, TEMP
        }
        component = true; // a weight: its components follow, then its grids
      }
      else if (component)
      {
        component = false;
      }
      else
      {
        this->addGrid(set, i, id);
        component = dependent;
      }
    }
  }

  // SPC1 SID C G1 G2 ... or SPC1 SID C G1 THRU G2: set "SPC1 <SID>".
  void constraint()
  {
    const std::int64_t id = this->integer(0, 0, "SID");
    NodeSetDefinition& set = this->nodeSet("SPC1 " + std::to_string(id));
    if (upperCase(this->field(3)) == "THRU")
    {
      const std::int64_t first = this->integer(2, id, "G1"), last = this->integer(4, id, "G2");
      if (last < first)
      {
        this->failField(4, "SPC1 " + std::to_string(first) + " THRU " + std::to_string(last) + " runs backwards");
      }
      set.items.push_back({ first, last, true, this->here() });
      return;
    }
    for (std::size_t i = 2; i < this->Current.fields.size(); ++i)
    {
      if (!this->field(i).empty())
      {
        this->addGrid(set, i, id);
      }
    }
  }

  // ---- once every entry is read ----

  std::size_t gridLine(std::size_t k) const
  {
    const GridSlot& slot = this->Out.slots[k];
    const std::string text = readFile(this->Out.files[slot.file]);
    return 1 + static_cast<std::size_t>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(slot.offset), '\n'));
  }

  [[noreturn]] void failGrid(std::size_t k, const std::string& reason) const
  {
    throw FileError(this->Out.files[this->Out.slots[k].file], this->gridLine(k), reason);
  }

  // Every grid's coordinates made basic, each slot given its system.
  void placeGrids()
  {
    const SourceMesh& mesh = this->Out.mesh;
    this->Grids = IdIndex(mesh.nodeIds);
    if (this->Grids.duplicate != IdIndex::none)
    {
      this->failGrid(this->Grids.duplicate, "GRID " + std::to_string(mesh.nodeIds[this->Grids.duplicate]) + " is defined twice");
    }
    this->Placed.assign(mesh.nodeIds.size(), 0);
    for (std::size_t k = 0; k < mesh.nodeIds.size(); ++k)
    {
      this->place(k);
    }
  }

  // Grid k's coordinates made basic (once).
  void place(std::size_t k)
  {
    if (this->Placed[k] == 2)
    {
      return;
    }
    const std::int64_t id = this->Out.mesh.nodeIds[k];
    if (this->Placed[k] == 1)
    {
      this->failGrid(k, "GRID " + std::to_string(id) + "'s position depends on itself (its CP system is defined through it)");
    }
    this->Placed[k] = 1;
    const std::int64_t cp = this->GridSystems[k] < 0 ? this->DefaultSystem : this->GridSystems[k];
    const std::uint32_t system = this->system(cp, [this, k] {
      return std::make_tuple(this->Out.slots[k].file, this->gridLine(k), "GRID " + std::to_string(this->Out.mesh.nodeIds[k]) + "'s CP");
    });
    this->Out.slots[k].system = system;
    if (system != 0)
    {
      toBasic(this->Out.systems[system], &this->Out.mesh.xyz[3 * k]);
    }
    this->Placed[k] = 2;
  }

  // What refers to a system, for an error: the file, the line and the words naming it.
  using Referrer = std::function<std::tuple<std::uint32_t, std::size_t, std::string>()>;

  // System id resolved into the basic one: its index in Out.systems.
  std::uint32_t system(std::int64_t id, const Referrer& referrer)
  {
    if (id == 0)
    {
      return 0;
    }
    const auto found = this->Definitions.find(id);
    if (found != this->Definitions.end() && found->second.state == 2)
    {
      return found->second.index;
    }
    auto failReferrer = [&](const std::string& reason) {
      const auto [file, line, words] = referrer();
      throw FileError(this->Out.files[file], line, words + " " + std::to_string(id) + reason);
    };
    if (found == this->Definitions.end())
    {
      failReferrer(" is not defined");
    }
    SystemDefinition& definition = found->second;
    const std::string subject = definition.card + " " + std::to_string(id);
    if (definition.state == 1)
    {
      throw FileError(this->Out.files[definition.file], definition.line, subject + " is defined through itself");
    }
    const char type = definition.card.back();
    if (definition.card.compare(0, 5, "CORD1") != 0 && definition.card.compare(0, 5, "CORD2") != 0)
    {
      failReferrer(" is a " + definition.card + ": only CORD1R/C/S and CORD2R/C/S are supported");
    }
    definition.state = 1;
    double points[9];
    if (definition.card[4] == '2')
    {
      const std::uint32_t reference = this->system(definition.reference, [&] {
        return std::make_tuple(definition.file, definition.line, subject + "'s RID");
      });
      std::copy(definition.points, definition.points + 9, points);
      for (int p = 0; p < 3 && reference != 0; ++p)
      {
        toBasic(this->Out.systems[reference], points + 3 * p);
      }
    }
    else
    {
      for (int g = 0; g < 3; ++g)
      {
        const std::size_t k = this->Grids.find(definition.grids[g]);
        if (k == IdIndex::none)
        {
          throw FileError(this->Out.files[definition.file], definition.line, subject + "'s grid " + std::to_string(definition.grids[g]) +
              " is not defined");
        }
        this->place(k);
        std::copy(&this->Out.mesh.xyz[3 * k], &this->Out.mesh.xyz[3 * k] + 3, points + 3 * g);
      }
    }
    // the origin A, the z axis towards B, the xz plane through C
    CoordinateSystem system;
    system.id = id;
    system.type = type;
    std::copy(points, points + 3, system.origin);
    double z[3], c[3], y[3];
    for (int a = 0; a < 3; ++a)
    {
      z[a] = points[3 + a] - points[a];
      c[a] = points[6 + a] - points[a];
    }
    const double zLength = std::sqrt(z[0] * z[0] + z[1] * z[1] + z[2] * z[2]);
    const double cLength = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    for (double& v : z)
    {
      v = zLength > 0 ? v / zLength : 0;
    }
    y[0] = z[1] * c[2] - z[2] * c[1];
    y[1] = z[2] * c[0] - z[0] * c[2];
    y[2] = z[0] * c[1] - z[1] * c[0];
    const double yLength = std::sqrt(y[0] * y[0] + y[1] * y[1] + y[2] * y[2]);
    if (!(yLength > 1e-12 * cLength))
    {
      throw FileError(this->Out.files[definition.file], definition.line, subject + "'s points A, B and C are on one line");
    }
    for (int a = 0; a < 3; ++a)
    {
      system.axes[1][a] = y[a] / yLength;
      system.axes[2][a] = z[a];
    }
    system.axes[0][0] = system.axes[1][1] * z[2] - system.axes[1][2] * z[1];
    system.axes[0][1] = system.axes[1][2] * z[0] - system.axes[1][0] * z[2];
    system.axes[0][2] = system.axes[1][0] * z[1] - system.axes[1][1] * z[0];
    this->Out.systems.push_back(system);
    definition.index = static_cast<std::uint32_t>(this->Out.systems.size() - 1);
    definition.state = 2;
    return definition.index;
  }

  // Every element's grids exist, each element id once; each solid turned as VTK's (Nastran takes
  // either: the QRG asks its grids' topology only).
  void checkElements()
  {
    SourceMesh& mesh = this->Out.mesh;
    std::vector<std::int64_t> elementIds;
    std::vector<std::uint64_t> where;
    for (std::size_t b = 0; b < mesh.blocks.size(); ++b)
    {
      ElementBlock& block = mesh.blocks[b];
      const std::size_t perCell = nodesPerCell(block.type);
      bool away = false;
      const int corners = solidCorners(block.type, away);
      const int base = corners == 4 || corners == 6 ? 3 : 4;
      std::vector<std::int64_t> cell(perCell);
      for (std::size_t e = 0; e < block.ids.size(); ++e)
      {
        std::int64_t* nodes = &block.nodes[e * perCell];
        std::array<const double*, 8> x{};
        for (std::size_t i = 0; i < perCell; ++i)
        {
          const std::size_t k = this->Grids.find(nodes[i]);
          if (k == IdIndex::none)
          {
            this->failAt(this->Where[b][e], block.name + " " + std::to_string(block.ids[e]) + " refers to grid " +
                std::to_string(nodes[i]) + ", which the deck does not define");
          }
          if (static_cast<int>(i) < corners)
          {
            x[i] = &mesh.xyz[3 * k];
          }
        }
        if (corners > 0 && turn(x.data(), corners, base) * (away ? -1 : 1) < 0)
        {
          const std::vector<int>& order = mirrored(block.type);
          std::copy(nodes, nodes + perCell, cell.begin());
          for (std::size_t i = 0; i < perCell; ++i)
          {
            nodes[i] = cell[order[i]];
          }
        }
        elementIds.push_back(block.ids[e]);
        where.push_back(this->Where[b][e]);
      }
    }
    const IdIndex elements(elementIds);
    if (elements.duplicate != IdIndex::none)
    {
      this->failAt(where[elements.duplicate], "element " + std::to_string(elementIds[elements.duplicate]) + " is defined twice");
    }
  }

  // How a solid's base face (its first base corners) turns: > 0 when its normal (right-hand rule)
  // points towards its other corners.
  static double turn(const double* const* x, int corners, int base)
  {
    // the normal u x v: a triangle's (x1 - x0) x (x2 - x0), a quadrilateral's diagonals' (x2 - x0) x (x3 - x1)
    double u[3], v[3], toward[3];
    for (int a = 0; a < 3; ++a)
    {
      u[a] = x[base == 3 ? 1 : 2][a] - x[0][a];
      v[a] = base == 3 ? x[2][a] - x[0][a] : x[3][a] - x[1][a];
      double baseSum = 0, otherSum = 0;
      for (int i = 0; i < corners; ++i)
      {
        (i < base ? baseSum : otherSum) += x[i][a];
      }
      toward[a] = otherSum / (corners - base) - baseSum / base;
    }
    return (u[1] * v[2] - u[2] * v[1]) * toward[0] + (u[2] * v[0] - u[0] * v[2]) * toward[1] + (u[0] * v[1] - u[1] * v[0]) * toward[2];
  }

  void resolveNodeSets()
  {
    const std::vector<std::int64_t>& ids = this->Out.mesh.nodeIds;
    std::vector<std::int64_t> sorted(ids);
    std::sort(sorted.begin(), sorted.end());
    for (const NodeSetDefinition& definition : this->NodeSets)
    {
      NamedSet set{ definition.name, {} };
      std::vector<char> taken(ids.size(), 0);
      auto add = [&](std::int64_t id) {
        const std::size_t k = this->Grids.find(id);
        if (k != IdIndex::none && !taken[k])
        {
          taken[k] = 1;
          set.ids.push_back(id);
        }
        return k != IdIndex::none;
      };
      for (const SetItem& item : definition.items)
      {
        if (item.range)
        {
          // the grids first THRU last that exist (the QRG does not ask them all to)
          for (auto id = std::lower_bound(sorted.begin(), sorted.end(), item.first); id != sorted.end() && *id <= item.last; ++id)
          {
            add(*id);
          }
        }
        else if (!add(item.first))
        {
          this->Out.mesh.warnings.push_back(this->Out.files[item.where >> 40] + ":" + std::to_string(item.where & LineBits) + ": grid " +
            std::to_string(item.first) + " is not in the deck: left out of set " + definition.name);
        }
      }
      this->Out.mesh.nodeSets.push_back(std::move(set));
    }
  }
};
} // namespace

Deck readDeck(const std::string& path)
{
  return std::move(Reader(path, false).Out);
}

Deck readNodeLayout(const std::string& path)
{
  return std::move(Reader(path, true).Out);
}

bool isNastran(const std::string& head)
{
  bool first = true, marked = false;
  for (const Line& span : lines(head))
  {
    const std::string_view line(head.data() + span.begin, span.end - span.begin);
    if (isComment(line))
    {
      continue;
    }
    const std::string word = leadingWord(line);
    const char after = line.size() > word.size() ? line[word.size()] : ' ';
    const bool separated = isBlank(after) || after == ',' || after == '*' || after == '=';
    // the first statement: a word (an executive statement, an entry's name) at the line's start
    if (first && (word.empty() || !std::isalpha(static_cast<unsigned char>(word[0])) || word.size() > 8 || !separated))
    {
      return false;
    }
    first = false;
    const std::string_view rest = trim(line.substr(word.size()));
    const std::string_view value = rest.substr(std::min(rest.find_first_not_of("*, \t"), rest.size()));
    const bool numbered = !value.empty() && std::isdigit(static_cast<unsigned char>(value[0]));
    marked = marked || word == "CEND" || (word == "BEGIN" && beginsBulk(line)) || (word == "SOL" && isBlank(after) && !value.empty()) ||
      ((word == "GRID" || elementCard(word)) && separated && numbered);
  }
  return marked;
}

// ---- the variant -------------------------------------------------------------------------------

namespace
{
// Appends line's text with fields replaced by their new texts (in the order of their columns): each
// in its columns (fixed field: aligned as the old text was, filling its width unless it ends the
// line; free field: between its commas), every other byte as it was, the comment after.
void appendLine(
  std::string& out, std::string_view text, const EntryLine& line, const std::vector<std::pair<const Field*, std::string>>& replaced)
{
  const std::string_view content = line.content;
  const std::size_t start = out.size();
  std::size_t at = 0, commas = 0;
  for (const auto& [field, value] : replaced)
  {
    const std::size_t begin = std::min<std::size_t>(field->begin, content.size());
    out.append(content.substr(at, begin - at));
    at = std::min<std::size_t>(field->end, content.size());
    if (line.free)
    {
      // a field after the line's last: its commas (those of a field added before it are written)
      out.append(field->commas - std::min<std::size_t>(commas, field->commas), ',');
      commas = field->commas;
      out.append(value);
      continue;
    }
    const std::size_t width = field->end - field->begin;
    out.append(field->begin - begin, ' ');
    const bool right = !field->text.empty() && field->text.data() > content.data() + field->begin &&
      field->text.data() + field->text.size() == content.data() + field->end;
    const std::size_t pad = width > value.size() ? width - value.size() : 0;
    out.append(right ? pad : 0, ' ');
    out.append(value);
    out.append(!right && at < content.size() ? pad : 0, ' ');
  }
  out.append(content.substr(at));
  const std::string_view whole(text.data() + line.begin, line.end - line.begin);
  const std::size_t comment = whole.find('$');
  if (comment != std::string_view::npos)
  {
    out.append(out.size() - start < content.size() ? content.size() - (out.size() - start) : 0, ' ');
    out.append(whole.substr(comment));
  }
}

// Appends to out the text of file f with each moved grid's coordinates replaced (row: where grid
// k's are in xyz).
void writeWithCoordinates(AtomicWrite::Aside& out, const Deck& deck, SourceBytes& file, std::uint32_t f,
  const std::vector<std::size_t>& row, const double* xyz)
{
  std::vector<std::size_t> mine; // the grids in file f, in file order
  for (std::size_t k = 0; k < deck.slots.size(); ++k)
  {
    if (deck.slots[k].file == f)
    {
      mine.push_back(k);
    }
  }
  rewriteInPieces(
    out, file, mine.size(), deck.gridsEnd[f], [&](std::size_t i) { return deck.slots[mine[i]].offset; },
    [&](std::string& piece, std::string_view text, std::size_t at, std::size_t i) {
      const std::size_t k = mine[i];
      const GridSlot& slot = deck.slots[k];
      std::size_t copied = at;
      thread_local Entry entry;
      thread_local std::vector<std::pair<const Field*, std::string>> replaced;
      readEntry(text, at, 0, deck.files[f], entry);
      const CoordinateSystem& system = deck.systems[slot.system];
      double old[3], basic[3], local[3];
      for (int c = 0; c < 3; ++c)
      {
        old[c] = 0;
        parseNastranReal(entry.fields[2 + c].text, old[c]);
        basic[c] = old[c];
      }
      if (slot.system != 0)
      {
        toBasic(system, basic);
      }
      const double* moved = xyz + 3 * row[k];
      if (basic[0] == moved[0] && basic[1] == moved[1] && basic[2] == moved[2])
      {
        return copied;
      }
      std::copy(moved, moved + 3, local);
      if (slot.system != 0)
      {
        toLocal(system, local, old);
      }
      for (std::uint32_t l = 0; l < entry.lines.size(); ++l)
      {
        const EntryLine& line = entry.lines[l];
        replaced.clear();
        for (int c = 0; c < 3; ++c)
        {
          const Field& field = entry.fields[2 + c];
          if (field.line == l && old[c] != local[c])
          {
            replaced.emplace_back(&field, nastranReal(local[c], line.free ? 32 : line.large ? 16 : 8));
          }
        }
        if (!replaced.empty())
        {
          piece.append(text, copied, line.begin - copied);
          appendLine(piece, text, line, replaced);
          copied = line.end;
        }
      }
      return copied;
    });
}
} // namespace

void Deck::writeVariant(const std::string& target, const std::int64_t* ids, const double* xyz, std::size_t count,
  bool overwrite) const
{
  const std::string& source = this->files.at(0);
  const std::vector<std::size_t> row = variantRows(target, source, this->mesh.nodeIds, ids, xyz, count);
  // each file's destination: the deck at target, a relative include beside it under its name
  std::vector<char> hasGrids(this->files.size(), 0);
  for (const GridSlot& slot : this->slots)
  {
    hasGrids[slot.file] = 1;
  }
  const std::vector<std::string> destinations = variantDestinations(target, this->files, this->includeNames, hasGrids);
  AtomicWrite write(overwrite);
  for (std::uint32_t f = 0; f < this->files.size(); ++f)
  {
    if (destinations[f].empty())
    {
      continue;
    }
    SourceBytes file(this->files[f], this->hashes[f], "deck");
    AtomicWrite::Aside out = write.open(destinations[f]);
    writeWithCoordinates(out, *this, file, f, row, xyz);
    write.close(out);
  }
  write.commit();
}
} // namespace nastran
} // namespace mlsformats
