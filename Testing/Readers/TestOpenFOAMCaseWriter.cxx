// vtkOpenFOAMCaseWriter on hand-made cases (no OpenFOAM needed): every points format, what is
// copied and what is not, and bad input that writes nothing (issue 12, point 1).
#include "../TestHarness.h"
#include "vtkOpenFOAMCaseWriter.h"

#include <vtkCharArray.h>
#include <vtkCommand.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkInformation.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkStringArray.h>
#include <vtkUnstructuredGrid.h>
#include <vtk_zlib.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;

namespace
{
const fs::path Root = fs::path(TEST_OUTPUT_DIR) / "openfoam-writer";

enum class Format
{
  Ascii,
  Binary,
  Compressed, // ascii, gzip
  Single      // binary, arch scalar=32
};

// n points with coordinates that are not floats: (i / 7, 1 + i / 3, -2 + i / 11) scaled
std::vector<double> sourcePoints(int n)
{
  std::vector<double> xyz;
  for (int i = 0; i < n; ++i)
  {
    xyz.push_back(i / 7.0);
    xyz.push_back(1 + i / 3.0);
    xyz.push_back(-2 + i / 11.0);
  }
  return xyz;
}

std::string header(Format format)
{
  const bool binary = format == Format::Binary || format == Format::Single;
  return std::string("/* a hand-made case */\nFoamFile\n{\n    version     2.0;\n    format      ") + (binary ? "binary" : "ascii") +
    ";\n    class       vectorField;\n    arch        \"LSB;label=32;scalar=" + (format == Format::Single ? "32" : "64") +
    "\";\n    location    \"constant/polyMesh\";\n    object      points;\n}\n// * * * //\n\n\n";
}

void writeText(const fs::path& path, const std::string& text)
{
  fs::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << text;
}

std::string pointsText(Format format, const std::vector<double>& xyz);

// A case: system, constant/polyMesh (points in the format, faces), 0/U and a result time 5/U,
// which a variant must not get.
fs::path makeCase(const std::string& name, Format format, const std::vector<double>& xyz)
{
  const fs::path dir = Root / name;
  fs::remove_all(dir);
  writeText(dir / "system" / "controlDict", "application simpleFoam;\n");
  writeText(dir / "constant" / "polyMesh" / "faces", "faces\n");
  writeText(dir / "constant" / "transportProperties", "nu 1e-5;\n");
  writeText(dir / "0" / "U", "initial\n");
  writeText(dir / "5" / "U", "result\n");
  const std::string text = pointsText(format, xyz);
  const fs::path points = dir / "constant" / "polyMesh" / "points";
  if (format == Format::Compressed)
  {
    fs::create_directories(points.parent_path());
    gzFile file = gzopen((points.string() + ".gz").c_str(), "wb");
    gzwrite(file, text.data(), static_cast<unsigned>(text.size()));
    gzclose(file);
  }
  else
  {
    writeText(points, text);
  }
  return dir;
}

// A points file's text in the format.
std::string pointsText(Format format, const std::vector<double>& xyz)
{
  std::string text = header(format) + std::to_string(xyz.size() / 3) + "\n(";
  if (format == Format::Binary || format == Format::Single)
  {
    for (double v : xyz)
    {
      const float f = static_cast<float>(v);
      text.append(format == Format::Single ? reinterpret_cast<const char*>(&f) : reinterpret_cast<const char*>(&v),
        format == Format::Single ? 4 : 8);
    }
  }
  else
  {
    std::ostringstream ascii;
    ascii.precision(12); // as OpenFOAM's writePrecision
    ascii << "\n";
    for (std::size_t i = 0; i < xyz.size(); i += 3)
      ascii << "(" << xyz[i] << " " << xyz[i + 1] << " " << xyz[i + 2] << ")\n";
    text += ascii.str();
  }
  text += ")\n\n// ***** //\n";
  return text;
}

// The case decomposed as decomposePar does (ascii): processor folders with their points (the
// whole mesh's points addressing[p][i]), pointProcAddressing and 0/U.
void decompose(const fs::path& dir, const std::vector<double>& xyz, const std::vector<std::vector<int>>& addressing)
{
  for (std::size_t p = 0; p < addressing.size(); ++p)
  {
    const fs::path processor = dir / ("processor" + std::to_string(p));
    std::vector<double> part;
    std::string labels = "FoamFile\n{\n    format      ascii;\n    class       labelList;\n    object      pointProcAddressing;\n}\n\n" +
      std::to_string(addressing[p].size()) + "\n(\n";
    for (int a : addressing[p])
    {
      part.insert(part.end(), { xyz[3 * a], xyz[3 * a + 1], xyz[3 * a + 2] });
      labels += std::to_string(a) + "\n";
    }
    writeText(processor / "constant" / "polyMesh" / "points", pointsText(Format::Ascii, part));
    writeText(processor / "constant" / "polyMesh" / "pointProcAddressing", labels + ")\n");
    writeText(processor / "constant" / "polyMesh" / "faces", "faces\n");
    writeText(processor / "0" / "U", "initial\n");
    writeText(processor / "5" / "U", "result\n");
  }
}

// The source's double coordinates as its file holds them (ascii: 12 digits).
std::vector<double> asStored(const std::vector<double>& xyz, Format format)
{
  std::vector<double> stored;
  for (double v : xyz)
  {
    std::ostringstream s;
    s.precision(12);
    s << v;
    stored.push_back(format == Format::Single ? static_cast<float>(v) : format == Format::Binary ? v : std::stod(s.str()));
  }
  return stored;
}

// What MLS Deform gives on what the OpenFOAM reader read: float points x_f moved by d (stored as
// float again), Displacement d, CasePath in the field data, extra points appended (Decompose
// polyhedra) after the case's.
vtkSmartPointer<vtkMultiBlockDataSet> deformedInput(
  const fs::path& casePath, const std::vector<double>& stored, const std::vector<double>& d, int extra = 0)
{
  const vtkIdType n = static_cast<vtkIdType>(stored.size() / 3);
  vtkNew<vtkPoints> points;
  points->SetDataTypeToFloat();
  vtkNew<vtkDoubleArray> displacement;
  displacement->SetName("Displacement");
  displacement->SetNumberOfComponents(3);
  for (vtkIdType i = 0; i < n + extra; ++i)
  {
    double moved[3], u[3];
    for (int c = 0; c < 3; ++c)
    {
      const double x = i < n ? stored[3 * i + c] : 0.5;
      u[c] = i < n ? d[3 * i + c] : 0.0;
      moved[c] = static_cast<float>(static_cast<float>(x) + u[c]);
    }
    points->InsertNextPoint(moved);
    displacement->InsertNextTuple(u);
  }
  vtkNew<vtkUnstructuredGrid> mesh;
  mesh->SetPoints(points);
  mesh->GetPointData()->AddArray(displacement);
  auto blocks = vtkSmartPointer<vtkMultiBlockDataSet>::New();
  blocks->SetBlock(0, mesh);
  blocks->GetMetaData(0u)->Set(vtkCompositeDataSet::NAME(), "internalMesh");
  vtkNew<vtkCharArray> path;
  path->SetName("CasePath");
  const std::string text = casePath.string() + "/";
  for (char c : text)
    path->InsertNextValue(c);
  path->InsertNextValue('\0');
  blocks->GetFieldData()->AddArray(path);
  return blocks;
}

std::vector<double> smallDisplacement(std::size_t size)
{
  std::vector<double> d;
  for (std::size_t i = 0; i < size; ++i)
    d.push_back(1e-3 * std::sin(static_cast<double>(i)));
  return d;
}

class ErrorCatcher : public vtkCommand
{
public:
  static ErrorCatcher* New() { return new ErrorCatcher; }
  void Execute(vtkObject*, unsigned long, void* data) override { Messages += static_cast<const char*>(data); }
  std::string Messages;
};

// Writes input to target; returns the error messages ("" on success).
std::string write(vtkDataObject* input, const fs::path& target, bool overwrite = false, bool link = false)
{
  vtkNew<vtkOpenFOAMCaseWriter> writer;
  vtkNew<ErrorCatcher> errors;
  writer->AddObserver(vtkCommand::ErrorEvent, errors);
  writer->SetInputData(input);
  writer->SetFileName((target / "case.foam").string().c_str());
  writer->SetOverwrite(overwrite);
  writer->SetLinkUnchangedFiles(link);
  writer->Write();
  CHECK((writer->GetErrorCode() != 0) == !errors->Messages.empty());
  return errors->Messages;
}

// Nothing partial of the target's next to it (the tests run concurrently in one folder).
bool noLeftovers(const fs::path& target)
{
  const std::string name = target.filename().string();
  for (const fs::directory_entry& e : fs::directory_iterator(target.parent_path()))
    if (e.path().filename().string().rfind(name + ".writing-", 0) == 0 || e.path().filename().string().rfind(name + ".replaced-", 0) == 0)
      return false;
  return true;
}

std::string content(const fs::path& path)
{
  gzFile file = gzopen(path.c_str(), "rb");
  std::string text;
  char buffer[4096];
  int read = 0;
  while (file && (read = gzread(file, buffer, sizeof(buffer))) > 0)
    text.append(buffer, static_cast<std::size_t>(read));
  if (file)
    gzclose(file);
  return text;
}

// The coordinates of a written points file, parsed here independently of the writer's reader:
// the count after the header, '(' and the coordinates.
std::vector<double> writtenPoints(const fs::path& polyMesh, Format format)
{
  const std::string text = content(polyMesh / (format == Format::Compressed ? "points.gz" : "points"));
  const std::size_t countAt = header(format).size();
  if (text.size() <= countAt)
    return {};
  const std::size_t n = std::stoul(text.substr(countAt, 20));
  const std::size_t begin = text.find('(', countAt) + 1;
  std::vector<double> xyz;
  if (format == Format::Binary || format == Format::Single)
  {
    for (std::size_t k = 0; k < 3 * n; ++k)
    {
      float f;
      double v;
      if (format == Format::Single)
        std::memcpy(&f, text.data() + begin + 4 * k, 4);
      else
        std::memcpy(&v, text.data() + begin + 8 * k, 8);
      xyz.push_back(format == Format::Single ? f : v);
    }
    return xyz;
  }
  std::istringstream lines(text.substr(begin));
  std::string line;
  while (std::getline(lines, line) && line != ")")
  {
    if (line.empty())
      continue;
    double x, y, z;
    if (std::sscanf(line.c_str(), "(%lf %lf %lf)", &x, &y, &z) == 3)
    {
      xyz.push_back(x);
      xyz.push_back(y);
      xyz.push_back(z);
    }
  }
  return xyz;
}
}

TEST(EveryPointsFormatRoundTrips)
{
  for (Format format : { Format::Ascii, Format::Binary, Format::Compressed, Format::Single })
  {
    const int n = 40000; // several of the chunks (16384 points) that ascii points are written in
    const std::vector<double> xyz = sourcePoints(n), d = smallDisplacement(3 * n);
    const std::string name = "source" + std::to_string(static_cast<int>(format));
    const fs::path source = makeCase(name, format, xyz);
    const std::vector<double> stored = asStored(xyz, format);
    const fs::path target = Root / (name + "-variant");
    fs::remove_all(target);
    const std::string errors = write(deformedInput(source, stored, d), target);
    std::printf("format %d: %s\n", static_cast<int>(format), errors.empty() ? "written" : errors.c_str());
    CHECK(errors.empty());
    // the source's double points plus the displacement, read back exactly (float for scalar=32)
    const std::vector<double> written = writtenPoints(target / "constant" / "polyMesh", format);
    CHECK(written.size() == stored.size());
    bool exact = written.size() == stored.size();
    for (std::size_t k = 0; exact && k < written.size(); ++k)
      exact = written[k] == (format == Format::Single ? static_cast<float>(stored[k] + d[k]) : stored[k] + d[k]);
    CHECK(exact);
    // the format is the source's: same header, compressed stays compressed
    const fs::path polyMesh = target / "constant" / "polyMesh";
    CHECK(fs::exists(polyMesh / "points.gz") == (format == Format::Compressed));
    CHECK(fs::exists(polyMesh / "points") == (format != Format::Compressed));
    CHECK(content(polyMesh / (format == Format::Compressed ? "points.gz" : "points")).rfind(header(format), 0) == 0);
    // a complete case without results
    CHECK(fs::exists(target / "case.foam") && fs::exists(target / "system" / "controlDict") && fs::exists(polyMesh / "faces") &&
      fs::exists(target / "constant" / "transportProperties") && fs::exists(target / "0" / "U"));
    CHECK(!fs::exists(target / "5"));
    CHECK(noLeftovers(target));
    // the source is untouched
    CHECK(content(source / "constant" / "polyMesh" / (format == Format::Compressed ? "points.gz" : "points")).find(")\n\n// ***** //") !=
      std::string::npos);
  }
}

// The decomposed reading (ParaView's OpenFOAM reader, Case Type Decomposed, on one process): each
// processor folder's points moved by the whole mesh's displacement at their point, then `centres`
// cell centres, the folders one after the other.
vtkSmartPointer<vtkMultiBlockDataSet> decomposedInput(const fs::path& casePath, const std::vector<double>& stored, const std::vector<double>& d,
  const std::vector<std::vector<int>>& addressing, int centres)
{
  std::vector<double> pieces, displacement;
  for (const std::vector<int>& part : addressing)
  {
    for (int a : part)
    {
      pieces.insert(pieces.end(), { stored[3 * a], stored[3 * a + 1], stored[3 * a + 2] });
      displacement.insert(displacement.end(), { d[3 * a], d[3 * a + 1], d[3 * a + 2] });
    }
    for (int c = 0; c < centres; ++c)
    {
      pieces.insert(pieces.end(), { 0.5 + c, 0.25, 0.125 }); // never a vertex
      displacement.insert(displacement.end(), { 0.0, 0.0, 0.0 });
    }
  }
  return deformedInput(casePath, pieces, displacement);
}

// The whole mesh's points moved by d, read back: exact?
bool movedExactly(const std::vector<double>& written, const std::vector<double>& stored, const std::vector<double>& d, const std::vector<int>& points)
{
  bool exact = written.size() == 3 * points.size();
  for (std::size_t i = 0; exact && i < points.size(); ++i)
    for (int c = 0; c < 3; ++c)
      exact = exact && written[3 * i + c] == stored[3 * points[i] + c] + d[3 * points[i] + c];
  return exact;
}

// Issue 14: a decomposed case gets every mesh moved, its processor folders and its reconstructed
// mesh, however the input was read.
// A case of 150 points decomposed into two processor folders that overlap and run backwards:
// processor0 holds points 0 .. 89, processor1 points 149 down to 60 (60 .. 89 shared).
struct DecomposedCase
{
  static constexpr int n = 150;
  std::vector<double> xyz = sourcePoints(n), d = smallDisplacement(3 * n);
  std::vector<double> stored = asStored(xyz, Format::Ascii);
  std::vector<std::vector<int>> addressing = std::vector<std::vector<int>>(2);
  std::vector<int> all = std::vector<int>(n);
  fs::path source;
  explicit DecomposedCase(const char* name)
  {
    for (int i = 0; i < 90; ++i)
      addressing[0].push_back(i);
    for (int i = n - 1; i >= 60; --i)
      addressing[1].push_back(i);
    for (int i = 0; i < n; ++i)
      all[i] = i;
    source = makeCase(name, Format::Ascii, xyz);
    decompose(source, xyz, addressing);
  }
};

TEST(DecomposedCaseMovesEveryMesh)
{
  const DecomposedCase c("processors");
  const std::vector<double>&stored = c.stored, &d = c.d;
  const std::vector<std::vector<int>>& addressing = c.addressing;
  const std::vector<int>& all = c.all;
  const fs::path& source = c.source;
  const fs::path target = Root / "processors-variant";
  auto check = [&](const char* reading) {
    std::printf("%s reading\n", reading);
    CHECK(movedExactly(writtenPoints(target / "constant" / "polyMesh", Format::Ascii), stored, d, all));
    for (int p = 0; p < 2; ++p)
    {
      const fs::path processor = target / ("processor" + std::to_string(p));
      CHECK(movedExactly(writtenPoints(processor / "constant" / "polyMesh", Format::Ascii), stored, d, addressing[p]));
      CHECK(fs::exists(processor / "constant" / "polyMesh" / "pointProcAddressing") && fs::exists(processor / "constant" / "polyMesh" / "faces") &&
        fs::exists(processor / "0" / "U") && !fs::exists(processor / "5"));
    }
    CHECK(noLeftovers(target));
  };
  // read reconstructed (Decompose polyhedra: 40 cell centres after the points)
  fs::remove_all(target);
  CHECK(write(deformedInput(source, stored, d, 40), target).empty());
  check("reconstructed");
  // read decomposed on one process: both folders, each with its cell centres after it
  fs::remove_all(target);
  CHECK(write(decomposedInput(source, stored, d, addressing, 7), target).empty());
  check("decomposed");
  // without a reconstructed mesh (decomposePar, then constant/polyMesh/points removed)
  fs::remove(source / "constant" / "polyMesh" / "points");
  fs::remove_all(target);
  CHECK(write(decomposedInput(source, stored, d, addressing, 0), target).empty());
  CHECK(!fs::exists(target / "constant" / "polyMesh" / "points"));
  for (int p = 0; p < 2; ++p)
    CHECK(movedExactly(writtenPoints(target / ("processor" + std::to_string(p)) / "constant" / "polyMesh", Format::Ascii), stored, d, addressing[p]));
}

TEST(LinkedVariantsHoldTheirPointsOnly)
{
  // LinkUnchangedFiles: every mesh's points are the variant's own files, moved as in a copy; every
  // other file, of the whole mesh and of each processor folder, links the source's
  const DecomposedCase c("linked");
  const std::vector<double>&stored = c.stored, &d = c.d;
  const fs::path& source = c.source;
  const fs::path target = Root / "linked-variant";
  fs::remove_all(target);
  CHECK(write(deformedInput(source, stored, d, 0), target, false, true).empty());
  CHECK(movedExactly(writtenPoints(target / "constant" / "polyMesh", Format::Ascii), stored, d, c.all));
  std::size_t links = 0, own = 0;
  for (const fs::directory_entry& e : fs::recursive_directory_iterator(target))
  {
    if (fs::is_symlink(e.symlink_status()))
    {
      ++links;
      const fs::path relative = fs::relative(e.path(), target);
      CHECK(fs::equivalent(e.path(), source / relative)); // the source's file at the same place
    }
    else if (fs::is_regular_file(e.symlink_status()))
    {
      ++own;
      CHECK(e.path().filename() == "points" || e.path().filename() == "case.foam");
    }
  }
  std::printf("%zu links, %zu own files\n", links, own);
  CHECK(links > 0 && own == 4); // the whole mesh's and two processors' points, and case.foam
  for (int p = 0; p < 2; ++p)
  {
    const fs::path polyMesh = target / ("processor" + std::to_string(p)) / "constant" / "polyMesh";
    CHECK(movedExactly(writtenPoints(polyMesh, Format::Ascii), stored, d, c.addressing[p]));
    CHECK(fs::is_symlink(polyMesh / "pointProcAddressing"));
  }
  CHECK(noLeftovers(target));
}

TEST(DecomposedPolyhedraPointsAreIgnored)
{
  const std::vector<double> xyz = sourcePoints(100), d = smallDisplacement(300);
  const fs::path source = makeCase("decomposed", Format::Ascii, xyz);
  const fs::path target = Root / "decomposed-variant";
  fs::remove_all(target);
  CHECK(write(deformedInput(source, asStored(xyz, Format::Ascii), d, 40), target).empty());
  CHECK(writtenPoints(target / "constant" / "polyMesh", Format::Ascii).size() == 300);
}

TEST(BadInputWritesNothing)
{
  const std::vector<double> xyz = sourcePoints(100), d = smallDisplacement(300);
  const fs::path source = makeCase("bad", Format::Ascii, xyz);
  const std::vector<double> stored = asStored(xyz, Format::Ascii);
  const fs::path target = Root / "bad-variant";
  fs::remove_all(target);
  auto listing = [](const fs::path& dir) {
    std::vector<std::string> names;
    if (fs::is_directory(dir))
      for (const fs::directory_entry& e : fs::recursive_directory_iterator(dir))
        names.push_back(e.path().string() + " " + std::to_string(e.is_regular_file() ? fs::file_size(e.path()) : 0));
    std::sort(names.begin(), names.end());
    return names;
  };
  auto expect = [&](vtkDataObject* input, const fs::path& to, const char* message, bool overwrite = false) {
    const bool existed = fs::exists(to);
    const std::vector<std::string> before = listing(to);
    const std::string errors = write(input, to, overwrite);
    std::printf("expected '%s': %s", message, errors.c_str());
    CHECK(errors.find(message) != std::string::npos);
    CHECK(fs::exists(to) == existed && listing(to) == before); // the target as it was
    CHECK(!fs::exists(to.parent_path()) || noLeftovers(to));
  };
  // no CasePath: not from an OpenFOAM case
  vtkSmartPointer<vtkMultiBlockDataSet> input = deformedInput(source, stored, d);
  input->GetFieldData()->RemoveArray("CasePath");
  expect(input, target, "no CasePath");
  // fewer points than the case
  const std::vector<double> fewer(stored.begin(), stored.begin() + 150);
  expect(deformedInput(source, fewer, d), target, "did not come from this case");
  // another mesh with as many points
  std::vector<double> other = stored;
  other[40] += 1e-3;
  expect(deformedInput(source, other, d), target, "did not come from this case");
  // no Displacement, and a failed deformation
  input = deformedInput(source, stored, d);
  vtkUnstructuredGrid::SafeDownCast(input->GetBlock(0))->GetPointData()->RemoveArray("Displacement");
  expect(input, target, "no point array Displacement");
  vtkNew<vtkStringArray> failure;
  failure->SetName("DeformationError");
  failure->InsertNextValue("no Handle region");
  input->GetFieldData()->AddArray(failure);
  expect(input, target, "the deformation failed (no Handle region)");
  // no internalMesh block
  input = deformedInput(source, stored, d);
  input->GetMetaData(0u)->Set(vtkCompositeDataSet::NAME(), "patch");
  expect(input, target, "no internalMesh block");
  // the source itself, an existing target, a folder that cannot be written
  expect(deformedInput(source, stored, d), source, "is the source case itself", true);
  CHECK(fs::exists(source / "5" / "U")); // the source keeps its results
  fs::create_directories(target / "system");
  writeText(target / "marker", "kept");
  writeText(target / "system" / "controlDict", "an earlier variant's");
  expect(deformedInput(source, stored, d), target, "exists");
  // a folder that is no OpenFOAM case is never replaced, even with Overwrite (a folder named for
  // the variant's .foam file would have its parent replaced)
  const fs::path mine = Root / "not-a-case";
  fs::create_directories(mine);
  writeText(mine / "precious.txt", "kept");
  expect(deformedInput(source, stored, d), mine, "is not an OpenFOAM case", true);
  expect(deformedInput(source, stored, d), "/proc/mlsdeform-variant", "cannot create");
  expect(deformedInput(source, stored, d), Root / "missing" / "variant", "does not exist");
  // a decomposed case whose processor folders hold another mesh, read reconstructed; a
  // decomposed reading that misses a folder; collated processor folders
  std::vector<double> elsewhere = stored;
  for (double& x : elsewhere)
    x += 0.01;
  decompose(source, elsewhere, { { 0, 1, 2 }, { 3, 4, 5 } });
  expect(deformedInput(source, stored, d), target, "not decomposed from this mesh", true);
  decompose(source, stored, { { 0, 1, 2 }, { 3, 4, 5 } });
  std::vector<double> firstFolder(stored.begin(), stored.begin() + 9);
  expect(deformedInput(source, firstFolder, d), target, "did not come from this case", true);
  fs::remove_all(source / "processor0");
  fs::remove_all(source / "processor1");
  fs::create_directories(source / "processors2");
  expect(deformedInput(source, stored, d), target, "collated", true);
  fs::remove_all(source / "processors2");
  // with Overwrite the existing target is replaced
  CHECK(write(deformedInput(source, stored, d), target, true).empty());
  CHECK(!fs::exists(target / "marker") && fs::exists(target / "constant" / "polyMesh" / "points") && noLeftovers(target));
}

TEST_MAIN
