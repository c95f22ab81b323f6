#include "Abaqus/CalculixAnalysis.h"

#include "Common/TextFile.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>

namespace mlsformats
{
namespace abaqus
{
namespace
{
std::string upper(std::string text)
{
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  return text;
}

std::string trimmed(const std::string& text)
{
  const std::size_t begin = text.find_first_not_of(" \t");
  const std::size_t end = text.find_last_not_of(" \t");
  return begin == std::string::npos ? std::string() : text.substr(begin, end - begin + 1);
}

// A data line's comma-separated fields, trimmed (a trailing comma leaves no empty last field).
std::vector<std::string> fieldsOf(const std::string& line)
{
  std::vector<std::string> fields;
  std::size_t begin = 0;
  while (begin <= line.size())
  {
    const std::size_t comma = line.find(',', begin);
    fields.push_back(trimmed(line.substr(begin, comma == std::string::npos ? std::string::npos : comma - begin)));
    if (comma == std::string::npos)
    {
      break;
    }
    begin = comma + 1;
  }
  while (!fields.empty() && fields.back().empty())
  {
    fields.pop_back();
  }
  return fields;
}

[[noreturn]] void refuse(const DeckKeyword& keyword, const std::string& reason)
{
  throw std::runtime_error(keyword.where + ": *" + keyword.name + ": " + reason);
}

double number(const DeckKeyword& keyword, const std::string& field, const char* what)
{
  char* end = nullptr;
  const double value = std::strtod(field.c_str(), &end);
  if (field.empty() || *end != '\0' || !std::isfinite(value))
  {
    refuse(keyword, std::string("\"") + field + "\" is not " + what);
  }
  return value;
}

bool integer(const std::string& field, std::int64_t& value)
{
  char* end = nullptr;
  value = std::strtoll(field.c_str(), &end, 10);
  return !field.empty() && *end == '\0';
}

// Output requests and the keywords of ccx's own sensitivity step: they change nothing in u.
bool harmless(const std::string& name)
{
  static const std::vector<std::string> names = { "NODE FILE", "EL FILE", "NODE PRINT", "EL PRINT", "NODE OUTPUT", "ELEMENT OUTPUT",
    "OUTPUT", "ELEMENT FILE", "SECTION PRINT", "DESIGNVARIABLES", "DESIGNRESPONSE", "SENSITIVITY", "OBJECTIVE", "CONSTRAINT",
    "PREPRINT", "RESTART", "ORIENTATION", "FILTER", "GEOMETRIC TOLERANCES" };
  return std::find(names.begin(), names.end(), name) != names.end();
}
} // namespace

std::vector<std::size_t> CalculixAnalysis::nodeSet(const std::string& name) const
{
  std::string known;
  for (const NamedSet& set : this->deck.mesh.nodeSets)
  {
    if (upper(set.name) == upper(name))
    {
      std::vector<std::size_t> nodes;
      for (std::int64_t id : set.ids)
      {
        nodes.push_back(this->nodeIndex(id));
      }
      return nodes;
    }
    known += (known.empty() ? "" : ", ") + set.name;
  }
  throw std::runtime_error("the deck has no node set " + name + " (its node sets: " + (known.empty() ? "none" : known) + ")");
}

std::vector<long> CalculixAnalysis::elementSet(const std::string& name) const
{
  std::string known;
  for (const NamedSet& set : this->deck.mesh.elementSets)
  {
    if (upper(set.name) == upper(name))
    {
      std::vector<long> elements;
      for (std::int64_t id : set.ids)
      {
        elements.push_back(this->elementIndex(id));
      }
      return elements;
    }
    known += (known.empty() ? "" : ", ") + set.name;
  }
  throw std::runtime_error("the deck has no element set " + name + " (its element sets: " + (known.empty() ? "none" : known) + ")");
}

std::size_t CalculixAnalysis::nodeIndex(std::int64_t id) const
{
  const std::size_t found = this->IndexOfNode->find(id);
  if (found == IdIndex::none)
  {
    throw std::runtime_error("the deck has no node " + std::to_string(id));
  }
  return found;
}

long CalculixAnalysis::elementIndex(std::int64_t id) const
{
  const std::size_t found = this->IndexOfElement->find(id);
  if (found == IdIndex::none)
  {
    throw std::runtime_error("the deck has no element " + std::to_string(id));
  }
  return static_cast<long>(found);
}

CalculixAnalysis readCalculixAnalysis(const std::string& path)
{
  CalculixAnalysis a;
  a.deck = readDeck(path);
  a.IndexOfNode.emplace(a.deck.mesh.nodeIds);
  std::vector<std::int64_t> elementIds;
  for (const ElementBlock& block : a.deck.mesh.blocks)
  {
    elementIds.insert(elementIds.end(), block.ids.begin(), block.ids.end());
  }
  a.IndexOfElement.emplace(elementIds);
  const long elements = static_cast<long>(elementIds.size());
  a.elementMaterial.assign(static_cast<std::size_t>(elements), -1);
  a.elementAcceleration.assign(static_cast<std::size_t>(elements), { 0, 0, 0 });
  const auto materialIndex = [&](const DeckKeyword& keyword, const std::string& name) {
    for (std::size_t m = 0; m < a.materials.size(); ++m)
    {
      if (upper(a.materials[m].name) == upper(name))
      {
        return static_cast<int>(m);
      }
    }
    refuse(keyword, "no *MATERIAL named " + name + " before it");
  };
  // the nodes a data line's first field names: a node id or a node set
  const auto nodesOf = [&](const DeckKeyword& keyword, const std::string& field) {
    std::int64_t id = 0;
    try
    {
      return integer(field, id) ? std::vector<std::size_t>{ a.nodeIndex(id) } : a.nodeSet(field);
    }
    catch (const std::runtime_error& error)
    {
      refuse(keyword, error.what());
    }
  };
  enum class Step
  {
    None,
    Static,
    Sensitivity
  } step = Step::None;
  bool inStep = false, staticRead = false;
  int material = -1;
  for (const DeckKeyword& keyword : a.deck.analysis)
  {
    const std::string& name = keyword.name;
    if (name == "MATERIAL")
    {
      a.materials.push_back({ keyword.get("NAME"), 0, 0, 0 });
      material = static_cast<int>(a.materials.size()) - 1;
    }
    else if (name == "ELASTIC" || name == "DENSITY")
    {
      if (material < 0)
      {
        refuse(keyword, "outside a *MATERIAL");
      }
      const std::string type = upper(keyword.get("TYPE"));
      if (name == "ELASTIC" && !type.empty() && type != "ISO")
      {
        refuse(keyword, "TYPE=" + type + ": only isotropic linear elastic materials (TYPE=ISO) are supported");
      }
      if (keyword.lines.size() != 1)
      {
        refuse(keyword, "temperature-dependent values (one data line expected, " + std::to_string(keyword.lines.size()) + " given)");
      }
      const std::vector<std::string> fields = fieldsOf(keyword.lines[0]);
      if (name == "ELASTIC")
      {
        if (fields.size() < 2)
        {
          refuse(keyword, "Young's modulus and Poisson's ratio expected");
        }
        a.materials[material].youngs = number(keyword, fields[0], "a Young's modulus");
        a.materials[material].poisson = number(keyword, fields[1], "a Poisson's ratio");
        if (!(a.materials[material].youngs > 0) || !(a.materials[material].poisson > -1 && a.materials[material].poisson < 0.5))
        {
          refuse(keyword, "E > 0 and -1 < nu < 0.5 expected");
        }
      }
      else
      {
        a.materials[material].density = number(keyword, fields.empty() ? "" : fields[0], "a density");
      }
    }
    else if (name == "SOLID SECTION")
    {
      const int m = materialIndex(keyword, keyword.get("MATERIAL"));
      std::vector<long> set;
      try
      {
        set = a.elementSet(keyword.get("ELSET"));
      }
      catch (const std::runtime_error& error)
      {
        refuse(keyword, error.what());
      }
      for (long e : set)
      {
        a.elementMaterial[e] = m;
      }
    }
    else if (name == "STEP")
    {
      const std::string nlgeom = upper(keyword.get("NLGEOM"));
      if (keyword.has("NLGEOM") && nlgeom != "NO")
      {
        refuse(keyword, "NLGEOM: only linear (small-displacement) analyses are supported");
      }
      if (keyword.has("PERTURBATION"))
      {
        refuse(keyword, "PERTURBATION steps are not supported");
      }
      inStep = true;
      step = Step::None;
    }
    else if (name == "END STEP")
    {
      inStep = false;
    }
    else if (name == "STATIC")
    {
      if (!inStep || staticRead)
      {
        refuse(keyword, staticRead ? "a second static step: one linear static step is supported" : "outside a *STEP");
      }
      staticRead = true;
      step = Step::Static;
    }
    else if (name == "SENSITIVITY")
    {
      step = Step::Sensitivity; // ccx's own derivatives: they change nothing of u
    }
    else if (name == "BOUNDARY" || name == "CLOAD")
    {
      if (step == Step::Sensitivity)
      {
        continue;
      }
      if (inStep && step != Step::Static)
      {
        refuse(keyword, "in a step that is not *STATIC");
      }
      if (name == "CLOAD" && !inStep)
      {
        refuse(keyword, "outside a step");
      }
      if (keyword.has("AMPLITUDE") || keyword.has("USER") || keyword.has("SUBMODEL") || keyword.has("FIXED") || keyword.has("MASS FLOW"))
      {
        refuse(keyword, "only plain values are supported (no AMPLITUDE, USER, SUBMODEL, FIXED)");
      }
      if (upper(keyword.get("OP")) == "NEW")
      {
        (name == "BOUNDARY" ? a.supports : a.loads).clear();
      }
      for (const std::string& line : keyword.lines)
      {
        const std::vector<std::string> fields = fieldsOf(line);
        if (fields.size() < 2)
        {
          refuse(keyword, "\"" + line + "\": a node or node set and a degree of freedom expected");
        }
        const std::vector<std::size_t> nodes = nodesOf(keyword, fields[0]);
        const int first = static_cast<int>(number(keyword, fields[1], "a degree of freedom"));
        const int last = name == "BOUNDARY" && fields.size() > 2 && !fields[2].empty() ? static_cast<int>(number(keyword, fields[2], "a degree of freedom")) : first;
        const double value = name == "BOUNDARY" ? (fields.size() > 3 ? number(keyword, fields[3], "a value") : 0.0)
                                                : (fields.size() > 2 ? number(keyword, fields[2], "a force") : 0.0);
        if (first < 1 || last > 3 || last < first)
        {
          refuse(keyword, "\"" + line + "\": degrees of freedom 1 to 3 (displacements) only; solids have no others");
        }
        for (std::size_t node : nodes)
        {
          for (int dof = first; dof <= last; ++dof)
          {
            (name == "BOUNDARY" ? a.supports : a.loads).push_back({ node, dof - 1, value });
          }
        }
      }
    }
    else if (name == "DLOAD")
    {
      if (step == Step::Sensitivity)
      {
        continue;
      }
      if (!inStep || step != Step::Static)
      {
        refuse(keyword, "outside a static step");
      }
      if (keyword.has("AMPLITUDE") || keyword.has("OP") && upper(keyword.get("OP")) != "MOD" && upper(keyword.get("OP")) != "NEW")
      {
        refuse(keyword, "only plain values are supported (no AMPLITUDE)");
      }
      if (upper(keyword.get("OP")) == "NEW")
      {
        std::fill(a.elementAcceleration.begin(), a.elementAcceleration.end(), std::array<double, 3>{ 0, 0, 0 });
        a.pressures.clear();
      }
      for (const std::string& line : keyword.lines)
      {
        const std::vector<std::string> fields = fieldsOf(line);
        const std::string label = fields.size() > 1 ? upper(fields[1]) : std::string();
        const bool pressure = label.size() == 2 && label[0] == 'P' && label[1] >= '1' && label[1] <= '6';
        if (label != "GRAV" && !pressure)
        {
          refuse(keyword, "\"" + line + "\": " + (label.empty() ? "no load label" : label) +
            " loads are not supported by the exact shape derivatives (pressure on a face, P1 to P6, and gravity, GRAV, are)");
        }
        if (fields.size() < (pressure ? 3u : 6u))
        {
          refuse(keyword, "\"" + line + "\": " + (pressure ? "a pressure needs its magnitude" : "GRAV needs the magnitude and the direction's three components"));
        }
        std::vector<long> elements;
        std::int64_t id = 0;
        try
        {
          elements = integer(fields[0], id) ? std::vector<long>{ a.elementIndex(id) } : a.elementSet(fields[0]);
        }
        catch (const std::runtime_error& error)
        {
          refuse(keyword, error.what());
        }
        const double magnitude = number(keyword, fields[2], pressure ? "a pressure" : "a magnitude");
        if (pressure)
        {
          for (long e : elements)
          {
            a.pressures.push_back({ e, label[1] - '0', magnitude });
          }
          continue;
        }
        // ccx normalizes the direction (bodyadd.f): the body force is rho times magnitude times it
        std::array<double, 3> direction = { number(keyword, fields[3], "a direction"), number(keyword, fields[4], "a direction"),
          number(keyword, fields[5], "a direction") };
        const double length = std::sqrt(direction[0] * direction[0] + direction[1] * direction[1] + direction[2] * direction[2]);
        if (!(length > 0))
        {
          refuse(keyword, "\"" + line + "\": the gravity's direction is zero");
        }
        for (long e : elements)
        {
          for (int c = 0; c < 3; ++c)
          {
            a.elementAcceleration[e][c] += magnitude * direction[c] / length;
          }
        }
      }
    }
    else if (!harmless(name))
    {
      refuse(keyword, "not supported by the exact shape derivatives (linear static analyses of isotropic solids under point loads, pressure and gravity)");
    }
  }
  if (!staticRead)
  {
    throw std::runtime_error(path + ": no *STATIC step: the exact shape derivatives need a linear static step");
  }
  for (long e = 0; e < elements; ++e)
  {
    if (a.elementMaterial[e] < 0)
    {
      throw std::runtime_error(path + ": element " + std::to_string(elementIds[e]) + " has no *SOLID SECTION");
    }
  }
  for (const IsotropicMaterial& m : a.materials)
  {
    if (!(m.youngs > 0))
    {
      throw std::runtime_error(path + ": *MATERIAL " + m.name + " has no *ELASTIC");
    }
  }
  return a;
}

namespace
{
// ccx's .frd (frd.c, frdvector.c): ASCII lines; a nodal block is a header line (the coordinates'
// "    2C", a result's "  100CL" then " -4 NAME" and its " -5" component lines) giving the node
// count and, in its last column, the format (1 ASCII, 2 binary floats, 3 binary doubles), then the
// nodes: " -1", the node in 10 columns and 12 columns a value, ended by " -3" (ASCII); or records
// of a 4-byte node number and the values (binary, no end line).
struct FrdFile
{
  std::string path, text;

  // The line starting at `at` (without "\n") and the offset after it.
  std::string line(std::size_t at, std::size_t& next) const
  {
    const std::size_t end = std::min(this->text.find('\n', at), this->text.size());
    next = std::min(end + 1, this->text.size());
    return this->text.substr(at, end - at);
  }

  // The nodes of the block whose data start at `at`, count nodes, `values` a node, format flag.
  std::map<std::int64_t, std::array<double, 3>> nodes(std::size_t at, long count, int values, char format, const char* what) const
  {
    std::map<std::int64_t, std::array<double, 3>> out;
    if (format == '1')
    {
      std::size_t next = at;
      for (std::string l = this->line(at, next); l.compare(0, 3, " -3") != 0; l = this->line(at = next, next))
      {
        if (at >= this->text.size())
        {
          throw FileError(this->path, 0, std::string("the ") + what + " block has no end (\" -3\")");
        }
        std::int64_t node = 0;
        std::array<double, 3> v{ 0, 0, 0 };
        if (l.compare(0, 3, " -1") != 0 || l.size() < 13 + 12 * 3 || !integer(trimmed(l.substr(3, 10)), node))
        {
          throw FileError(this->path, 0, std::string("not a nodal line of three values in the ") + what + " block: \"" + l + "\"");
        }
        for (int c = 0; c < 3; ++c)
        {
          const std::string field = l.substr(13 + 12 * c, 12);
          char* end = nullptr;
          v[c] = std::strtod(field.c_str(), &end);
          if (end == field.c_str() || !std::isfinite(v[c]))
          {
            throw FileError(this->path, 0, "\"" + field + "\" is not a number (" + what + ")");
          }
        }
        out[node] = v;
      }
      return out;
    }
    const std::size_t size = format == '2' ? 4 : 8, record = 4 + size * static_cast<std::size_t>(values);
    if (count < 0 || at + record * static_cast<std::size_t>(count) > this->text.size())
    {
      throw FileError(this->path, 0, std::string("the binary ") + what + " block is cut short");
    }
    for (long n = 0; n < count; ++n, at += record)
    {
      std::int32_t node = 0;
      std::memcpy(&node, this->text.data() + at, 4);
      std::array<double, 3> v{ 0, 0, 0 };
      for (int c = 0; c < 3; ++c)
      {
        if (size == 4)
        {
          float f = 0;
          std::memcpy(&f, this->text.data() + at + 4 + 4 * c, 4);
          v[c] = f;
        }
        else
        {
          std::memcpy(&v[c], this->text.data() + at + 4 + 8 * c, 8);
        }
      }
      out[node] = v;
    }
    return out;
  }
};

// The node count (the whitespace-separated field `field`) and the format flag of a header line.
void headerOf(const std::string& line, int field, long& count, char& format)
{
  std::istringstream fields(line);
  std::string token;
  for (int k = 0; k <= field && fields >> token; ++k)
  {
  }
  count = std::strtol(token.c_str(), nullptr, 10);
  const std::string last = trimmed(line);
  format = last.empty() ? '1' : last.back(); // the line's last column (74 for 2C, 75 for 100CL)
}
} // namespace

FrdDisplacements readFrdDisplacements(const std::string& path)
{
  FrdFile frd{ path, {} };
  {
    std::ifstream file(path, std::ios::binary);
    if (!file)
    {
      throw FileError(path, 0, "cannot be read (a ccx result file, JOB.frd)");
    }
    frd.text.assign(std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>());
  }
  FrdDisplacements out;
  std::size_t next = 0;
  const std::size_t coordinates = frd.text.find("\n    2C");
  if (coordinates == std::string::npos)
  {
    throw FileError(path, 0, "holds no node coordinates (its 2C block): is it a ccx result file?");
  }
  long count = 0;
  char format = '1';
  headerOf(frd.line(coordinates + 1, next), 1, count, format);
  out.coordinates = frd.nodes(next, count, 3, format == '1' ? '1' : '3', "coordinates"); // binary coordinates are doubles
  // the last DISP block: its " -4" line, the "  100CL" line before it, the " -5" lines after
  const std::size_t block = frd.text.rfind("\n -4  DISP ");
  const std::size_t header = block == std::string::npos ? block : frd.text.rfind("\n  100C", block);
  if (block == std::string::npos || header == std::string::npos)
  {
    throw FileError(path, 0, "holds no displacements (DISP): request them with *NODE FILE and U in the static step "
                             "(*NODE FILE, DOUBLE writes them in full precision)");
  }
  headerOf(frd.line(header + 1, next), 3, count, format);
  frd.line(block + 1, next);
  int values = 0;
  for (std::size_t at = next; frd.text.compare(at, 3, " -5") == 0; at = next)
  {
    const std::string component = frd.line(at, next);
    values += component.find("ALL", 5) == std::string::npos ? 1 : 0; // ALL: the magnitude, not stored
  }
  if (values != 3)
  {
    throw FileError(path, 0, "its DISP block has " + std::to_string(values) + " components, not 3");
  }
  out.displacements = frd.nodes(next, count, 3, format, "DISP");
  return out;
}
} // namespace abaqus
} // namespace mlsformats
