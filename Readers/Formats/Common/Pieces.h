// A file's text rewritten node by node in pieces formatted side by side: how the text formats
// write a variant of a large file on every thread (the same bytes for any number of threads).
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace mlsformats
{
/// A text with its nodes' text rewritten: the source's own bytes before the first node and after
/// the last (views into it, not copied), and between them the formatted pieces, to be written
/// one after the other (AtomicWrite::add).
struct RewrittenText
{
  std::vector<std::string> formatted;
  std::vector<std::string_view> pieces;
};

/// The text with the old text of each of nodes (in file order, node i's starting at begin(i))
/// replaced by what write(out, i) appends to out (returning where node i's old text ends),
/// formatted in 64 pieces side by side. The result's views are into text: keep it alive.
template <class Begin, class Write>
RewrittenText rewriteInPieces(std::string_view text, std::size_t nodes, Begin begin, Write write)
{
  RewrittenText out;
  const std::string_view whole = text;
  if (nodes == 0)
  {
    out.pieces.push_back(whole);
    return out;
  }
  constexpr long Pieces = 64;
  out.formatted.resize(Pieces);
  std::vector<std::size_t> ends(Pieces, 0);
  // piece p: its nodes' text and what follows up to the next piece's first node (the last
  // piece: up to the end of the last node's text)
#pragma omp parallel for schedule(dynamic)
  for (long p = 0; p < Pieces; ++p)
  {
    const std::size_t first = nodes * p / Pieces, last = nodes * (p + 1) / Pieces;
    if (first == last)
    {
      continue;
    }
    std::string& piece = out.formatted[p];
    std::size_t copied = static_cast<std::size_t>(begin(first));
    const std::size_t next = last < nodes ? static_cast<std::size_t>(begin(last)) : static_cast<std::size_t>(begin(last - 1));
    piece.reserve((next - copied) * 9 / 8 + 256);
    for (std::size_t i = first; i < last; ++i)
    {
      const std::size_t at = static_cast<std::size_t>(begin(i));
      piece.append(text, copied, at - copied);
      copied = write(piece, i);
    }
    if (last < nodes)
    {
      piece.append(text, copied, next - copied);
      copied = next;
    }
    ends[p] = copied;
  }
  out.pieces.push_back(whole.substr(0, static_cast<std::size_t>(begin(0))));
  for (const std::string& piece : out.formatted)
  {
    out.pieces.push_back(piece);
  }
  out.pieces.push_back(whole.substr(ends[Pieces - 1]));
  return out;
}
} // namespace mlsformats
