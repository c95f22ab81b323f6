#include "vtkOFFReader.h"

#include <vtkCellArray.h>
#include <vtkFloatArray.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkUnsignedCharArray.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

vtkStandardNewMacro(vtkOFFReader);

namespace
{
// Whitespace-separated tokens with '#' comments removed, line structure kept for face colors.
class Tokens
{
public:
  explicit Tokens(std::istream& in)
    : In(in)
  {
  }
  bool next(std::string& token)
  {
    while (!(Line >> token))
    {
      std::string text;
      if (!std::getline(In, text))
      {
        return false;
      }
      const std::size_t comment = text.find('#');
      if (comment != std::string::npos)
      {
        text.erase(comment);
      }
      Line.clear();
      Line.str(text);
    }
    return true;
  }
  template <typename T>
  T number(const char* what)
  {
    std::string token;
    if (!next(token))
    {
      throw std::runtime_error(std::string("unexpected end of file while reading ") + what);
    }
    std::istringstream s(token);
    T value;
    if (!(s >> value))
    {
      throw std::runtime_error(std::string("'") + token + "' is not a valid " + what);
    }
    return value;
  }
  /// Drops the rest of the current line (e.g. a face's color).
  void skipLine() { Line.str(""); }

private:
  std::istream& In;
  std::istringstream Line;
};

struct Header
{
  bool texture = false, color = false, normal = false;
};

bool parseHeader(const std::string& word, Header& header)
{
  // [ST][C][N][4][n]OFF: only 3D files are supported
  std::size_t i = 0;
  if (word.compare(i, 2, "ST") == 0)
  {
    header.texture = true;
    i += 2;
  }
  for (; i < word.size() && word[i] != 'O'; ++i)
  {
    if (word[i] == 'C')
      header.color = true;
    else if (word[i] == 'N')
      header.normal = true;
    else
      return false;
  }
  return word.compare(i, std::string::npos, "OFF") == 0;
}
}

vtkOFFReader::vtkOFFReader()
{
  this->SetNumberOfInputPorts(0);
}

int vtkOFFReader::CanReadFile(const char* filename)
{
  std::ifstream in(filename ? filename : "");
  Tokens tokens(in);
  std::string word;
  Header header;
  return in && tokens.next(word) && parseHeader(word, header) ? 1 : 0;
}

int vtkOFFReader::RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  std::ifstream in(this->FileName);
  if (this->FileName.empty() || !in)
  {
    vtkErrorMacro(<< "Cannot open OFF file '" << this->FileName << "'.");
    return 0;
  }
  in.seekg(0, std::ios::end);
  const long long size = in.tellg();
  const long long bytes = size >= 0 ? size : std::numeric_limits<long long>::max(); // (not seekable: no bound)
  in.clear();
  in.seekg(0);
  try
  {
    Tokens tokens(in);
    std::string word;
    Header header;
    if (!tokens.next(word) || !parseHeader(word, header))
    {
      throw std::runtime_error("the file does not start with an OFF, COFF or NOFF header");
    }
    const long nv = tokens.number<long>("vertex count");
    const long nf = tokens.number<long>("face count");
    tokens.number<long>("edge count");
    if (nv < 0 || nf < 0)
    {
      throw std::runtime_error("negative vertex or face count");
    }
    // A vertex takes at least 6 bytes ("0 0 0\n"), a face at least 4 ("1 0\n"): larger counts
    // are a damaged header, refused before anything of their size is allocated.
    if (6.0 * nv + 4.0 * nf > static_cast<double>(bytes))
    {
      throw std::runtime_error("the header announces " + std::to_string(nv) + " vertices and " + std::to_string(nf) + " faces, more than the file's " +
        std::to_string(bytes) + " bytes can hold");
    }
    vtkNew<vtkPoints> points;
    points->SetNumberOfPoints(nv);
    vtkNew<vtkFloatArray> normals;
    normals->SetNumberOfComponents(3);
    normals->SetName("Normals");
    vtkNew<vtkUnsignedCharArray> colors;
    colors->SetNumberOfComponents(4);
    colors->SetName("Colors");
    for (long i = 0; i < nv; ++i)
    {
      double x[3];
      for (double& c : x)
      {
        c = tokens.number<double>("vertex coordinate");
      }
      points->SetPoint(i, x);
      if (header.normal)
      {
        float n[3];
        for (float& c : n)
        {
          c = tokens.number<float>("normal component");
        }
        normals->InsertNextTuple3(n[0], n[1], n[2]);
      }
      if (header.color)
      {
        double rgba[4] = { 0, 0, 0, 255 };
        for (int c = 0; c < 4; ++c)
        {
          rgba[c] = tokens.number<double>("color component");
        }
        const bool unit = rgba[0] <= 1 && rgba[1] <= 1 && rgba[2] <= 1 && rgba[3] <= 1;
        for (double& c : rgba)
        {
          c = std::round(unit ? 255 * c : c);
        }
        colors->InsertNextTuple4(rgba[0], rgba[1], rgba[2], rgba[3]);
      }
      if (header.texture)
      {
        tokens.number<double>("texture coordinate");
        tokens.number<double>("texture coordinate");
      }
      tokens.skipLine();
      if (i % 100000 == 0)
      {
        this->UpdateProgress(0.5 * i / std::max(1L, nv));
      }
    }
    vtkNew<vtkCellArray> polygons;
    std::vector<vtkIdType> ids;
    for (long f = 0; f < nf; ++f)
    {
      const long n = tokens.number<long>("face size");
      if (n < 1 || 2.0 * n > static_cast<double>(bytes)) // a face of n vertices takes at least 2n bytes
      {
        throw std::runtime_error("face " + std::to_string(f) + " has " + std::to_string(n) + " vertices");
      }
      ids.resize(n);
      for (vtkIdType& id : ids)
      {
        id = tokens.number<long>("vertex index");
        if (id < 0 || id >= nv)
        {
          throw std::runtime_error("face " + std::to_string(f) + " refers to vertex " + std::to_string(id) + " of " + std::to_string(nv));
        }
      }
      tokens.skipLine(); // optional face color
      polygons->InsertNextCell(n, ids.data());
      if (f % 100000 == 0)
      {
        this->UpdateProgress(0.5 + 0.5 * f / std::max(1L, nf));
      }
    }
    output->SetPoints(points);
    output->SetPolys(polygons);
    if (header.normal)
    {
      output->GetPointData()->SetNormals(normals);
    }
    if (header.color)
    {
      output->GetPointData()->AddArray(colors);
    }
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< "Cannot read OFF file '" << this->FileName << "': " << e.what());
    output->Initialize();
    return 0;
  }
  return 1;
}

void vtkOFFReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
}
