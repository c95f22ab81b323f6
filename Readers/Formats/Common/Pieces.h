// A file's text written with its nodes' text rewritten, in pieces formatted side by side and
// written in order as they are done: how the text formats write a variant of a large file on
// every thread (the same bytes for any number of threads), formatting one piece while the one
// before is written.
#pragma once

#include "Common/TextFile.h"

#include <cstddef>
#include <string>
#include <string_view>

namespace mlsformats
{
/// Appends to out the text with the old text of each of nodes (in file order, node i's starting
/// at begin(i)) replaced by what write(piece, i) appends to piece (returning where node i's old
/// text ends). The nodes are formatted in 64 pieces, each appended to out as soon as those before
/// it are: the bytes before the first node and after the last go from text to out uncopied.
template <class Begin, class Write>
void rewriteInPieces(AtomicWrite::Aside& out, std::string_view text, std::size_t nodes, Begin begin, Write write)
{
  if (nodes == 0)
  {
    out.append(text);
    return;
  }
  out.append(text.substr(0, static_cast<std::size_t>(begin(0))));
  constexpr long Pieces = 64;
  std::size_t end = 0; // where the last piece's text ends
#pragma omp parallel
  {
    std::string piece; // this thread's, reused piece after piece
    // piece p: its nodes' text and what follows up to the next piece's first node (the last
    // piece: up to the end of the last node's text)
#pragma omp for ordered schedule(dynamic, 1)
    for (long p = 0; p < Pieces; ++p)
    {
      const std::size_t first = nodes * p / Pieces, last = nodes * (p + 1) / Pieces;
      piece.clear();
      if (first < last)
      {
        std::size_t copied = static_cast<std::size_t>(begin(first));
        const std::size_t next = last < nodes ? static_cast<std::size_t>(begin(last)) : copied;
        piece.reserve((static_cast<std::size_t>(begin(last - 1)) - copied) * 9 / 8 + 256);
        for (std::size_t i = first; i < last; ++i)
        {
          const std::size_t at = static_cast<std::size_t>(begin(i));
          piece.append(text, copied, at - copied);
          copied = write(piece, i);
        }
        if (last < nodes)
        {
          piece.append(text, copied, next - copied);
        }
        else
        {
          end = copied;
        }
      }
#pragma omp ordered
      out.append(piece);
    }
  }
  out.append(text.substr(end));
}
} // namespace mlsformats
