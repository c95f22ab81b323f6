// What every format's variant is written with (Readers/Formats/Common): a text rewritten in pieces
// side by side against the same text rewritten node by node, on files that span several of the
// source hash's 4 MiB chunks (the format tests' files span one); a source changed since it was read
// (in the bytes copied, in the node span, cut short) and a node that cannot be written are errors
// that leave nothing behind, not a crash.
#include "FormatFiles.h"

#include "Common/Pieces.h"
#include "Common/TextFile.h"

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace
{
using mlsformats::AtomicWrite;
using mlsformats::FileError;
using mlsformats::SourceBytes;
using testing::contains;
using testing::writeFile;
const testing::TestFolders folder{ "variantwriting" };

// A text of about 12 MiB: a head, nodes "x y z" (one a line, 300k of them: about 6 MiB) and a tail,
// each longer than a hash chunk, so that head, node span and tail each cross chunk bounds.
struct NodeText
{
  std::string text;
  std::vector<std::size_t> begins; // where each node's x starts
  std::vector<double> xyz;         // the nodes' coordinates as written
  std::size_t end = 0;             // where the last node's z ends
};

NodeText nodeText()
{
  NodeText out;
  const std::string filler(3 << 20, '#');
  out.text = "head\n" + filler + "\n$Nodes\n";
  for (std::size_t i = 0; i < 300000; ++i)
  {
    const double x = 0.5 * i, y = 1.0 / (i + 3), z = -0.25;
    out.begins.push_back(out.text.size());
    std::string line;
    mlsformats::appendShortest(line, x);
    line += ' ';
    mlsformats::appendShortest(line, y);
    line += "  ";
    mlsformats::appendShortest(line, z);
    out.text += line;
    out.end = out.text.size();
    out.text += i % 1000 == 999 ? "\n% a comment between nodes\n" : "\n";
    out.xyz.insert(out.xyz.end(), { x, y, z });
  }
  out.text += "$EndNodes\n" + filler + "\ntail\n";
  return out;
}

// The text written node by node: every fifth node moved, the others kept as they were.
std::vector<double> moved(const NodeText& nodes)
{
  std::vector<double> xyz = nodes.xyz;
  for (std::size_t i = 0; i < xyz.size() / 3; i += 5)
  {
    xyz[3 * i + 1] += 1e-3 * static_cast<double>(i % 7);
  }
  return xyz;
}

std::string expectedText(const NodeText& nodes, const std::vector<double>& xyz)
{
  std::string out;
  std::size_t copied = 0;
  for (std::size_t i = 0; i < nodes.begins.size(); ++i)
  {
    out.append(nodes.text, copied, nodes.begins[i] - copied);
    copied = mlsformats::appendNumbers(out, nodes.text, nodes.begins[i], 3, xyz.data() + 3 * i);
  }
  out.append(nodes.text, copied, std::string::npos);
  return out;
}

// Writes the variant of source (read as nodes) with xyz to target; the error, or "".
std::string writeVariant(const NodeText& nodes, const std::string& source, const std::string& target, const std::vector<double>& xyz,
  std::size_t throwAt = std::string::npos)
{
  try
  {
    SourceBytes file(source, mlsformats::contentHash(nodes.text));
    AtomicWrite write(true);
    AtomicWrite::Aside out = write.open(target);
    mlsformats::rewriteInPieces(
      out, file, nodes.begins.size(), nodes.end, [&](std::size_t i) { return nodes.begins[i]; },
      [&](std::string& piece, std::string_view text, std::size_t at, std::size_t i) {
        if (i == throwAt)
        {
          throw std::runtime_error("node " + std::to_string(i) + " cannot be written");
        }
        return mlsformats::appendNumbers(piece, text, at, 3, xyz.data() + 3 * i, nodes.xyz.data() + 3 * i);
      });
    write.close(out);
    write.commit();
    return "";
  }
  catch (const std::exception& e)
  {
    return e.what();
  }
}
} // namespace

TEST(PiecesWriteWhatNodeByNodeWrites)
{
  const std::string dir = folder("pieces");
  const NodeText nodes = nodeText();
  const std::string source = writeFile(dir + "/source.txt", nodes.text);
  const std::vector<double> xyz = moved(nodes);
  CHECK(writeVariant(nodes, source, dir + "/variant/a.txt", xyz).empty());
  CHECK(mlsformats::readFile(dir + "/variant/a.txt") == expectedText(nodes, xyz));
  // nothing moved: the source, byte for byte
  CHECK(writeVariant(nodes, source, dir + "/variant/same.txt", nodes.xyz).empty());
  CHECK(mlsformats::readFile(dir + "/variant/same.txt") == nodes.text);
  CHECK(testing::nothingWrittenAside(dir));
}

TEST(ChangedSourceOrFailedNodeLeavesNothing)
{
  const std::string dir = folder("refusals");
  const NodeText nodes = nodeText();
  const std::string source = dir + "/source.txt";
  const std::vector<double> xyz = moved(nodes);
  const std::string target = dir + "/made/for/variant.txt";
  // a byte in the tail (copied, never parsed), a byte in the node span, the file cut short
  std::string inTail = nodes.text, inNodes = nodes.text;
  inTail[inTail.size() - 100] = '%';
  inNodes[nodes.begins[150000] - 1] = '\t';
  for (const std::string& changed : { inTail, inNodes, nodes.text.substr(0, nodes.text.size() - (5 << 20)),
         nodes.text.substr(0, nodes.begins[200000]) })
  {
    writeFile(source, changed);
    const std::string error = writeVariant(nodes, source, target, xyz);
    CHECK(contains(error, source + ": has changed since it was read"));
    CHECK(!std::filesystem::exists(dir + "/made"));
  }
  // a node that throws: thrown once the pieces are done (not out of the threads), nothing written
  writeFile(source, nodes.text);
  CHECK(writeVariant(nodes, source, target, xyz, 123456) == "node 123456 cannot be written");
  CHECK(!std::filesystem::exists(dir + "/made"));
  CHECK(testing::nothingWrittenAside(dir));
}

TEST_MAIN
