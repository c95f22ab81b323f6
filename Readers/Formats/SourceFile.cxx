#include "SourceFile.h"

#include "Abaqus/AbaqusDeck.h"
#include "CGNS/CgnsMesh.h"
#include "Fluent/FluentMesh.h"
#include "Exodus/ExodusMesh.h"
#include "Gmsh/GmshMesh.h"
#include "Nastran/NastranDeck.h"
#include "SU2/SU2Mesh.h"
#include "Common/TextFile.h"

#include <algorithm>
#include <cctype>
#include <sstream>

namespace mlsformats
{
namespace
{
// A deck starts with a keyword or a comment ("*HEADING", "**"), after blank lines.
bool isDeck(const std::string& text)
{
  const std::size_t first = text.find_first_not_of(" \t\r\n");
  return first != std::string::npos && text[first] == '*';
}

std::unique_ptr<SourceFile> readDeck(const std::string& path, bool layout)
{
  return std::make_unique<abaqus::Deck>(layout ? abaqus::readNodeLayout(path) : abaqus::readDeck(path));
}

std::unique_ptr<SourceFile> readGmsh(const std::string& path, bool layout)
{
  return std::make_unique<gmsh::MshFile>(layout ? gmsh::readMshLayout(path) : gmsh::readMsh(path));
}

std::unique_ptr<SourceFile> readSu2Mesh(const std::string& path, bool layout)
{
  return std::make_unique<su2::MeshFile>(layout ? su2::readSu2Layout(path) : su2::readSu2(path));
}

std::unique_ptr<SourceFile> readFluentMesh(const std::string& path, bool layout)
{
  return std::make_unique<fluent::MeshFile>(layout ? fluent::readFluentLayout(path) : fluent::readFluent(path));
}

std::unique_ptr<SourceFile> readNastran(const std::string& path, bool layout)
{
  return std::make_unique<nastran::Deck>(layout ? nastran::readNodeLayout(path) : nastran::readDeck(path));
}

std::unique_ptr<SourceFile> readExodusMesh(const std::string& path, bool layout)
{
  return std::make_unique<exodus::MeshFile>(layout ? exodus::readExodusLayout(path) : exodus::readExodus(path));
}

std::unique_ptr<SourceFile> readCgnsMesh(const std::string& path, bool layout)
{
  return std::make_unique<cgns::MeshFile>(layout ? cgns::readCgnsLayout(path) : cgns::readCgns(path));
}

std::string lowerCase(std::string text)
{
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}
} // namespace

const std::vector<Format>& formats()
{
  static const std::vector<Format> table = {
    { "Abaqus/CalculiX deck", "inp", true, isDeck, readDeck },
    { "Gmsh mesh", "msh", true, gmsh::isMsh, readGmsh },
    { "SU2 mesh", "su2", false, su2::isSu2, readSu2Mesh },
    { "Fluent mesh", "msh cas", false, fluent::isFluent, readFluentMesh },
    { "Nastran bulk data", "bdf nas dat", true, nastran::isNastran, readNastran },
    { "Exodus II mesh", "exo e ex2 g", true, exodus::isExodus, readExodusMesh },
    { "CGNS mesh", "cgns", false, cgns::isCgns, readCgnsMesh },
  };
  return table;
}

const Format* formatOf(const std::string& path)
{
  const std::size_t dot = path.find_last_of('.');
  const std::string extension = dot == std::string::npos ? std::string() : lowerCase(path.substr(dot + 1));
  const std::string head = readHead(path, 4096);
  for (const Format& format : formats())
  {
    std::istringstream extensions(format.extensions);
    std::string known;
    while (extensions >> known)
    {
      if (known == extension && format.recognizes(head))
      {
        return &format;
      }
    }
  }
  return nullptr;
}
} // namespace mlsformats
