// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "vtkNumpyGridReader.h"

#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkObjectFactory.h"

#include <vtksys/FStream.hxx>
#include <vtksys/SystemTools.hxx>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkNumpyGridReader);

namespace
{
// Same bound as the other horizon readers: 2^31 nodes or more is a corrupt header, not a horizon.
constexpr long long MaxNodes = 2147483647LL;
// numpy itself writes headers of a few hundred bytes; anything beyond this is not a header.
constexpr long long MaxHeaderLength = 1LL << 24;
// Values are read and converted in chunks of this many elements, so memory stays at the output
// array plus one chunk however large the file is.
constexpr vtkIdType ChunkElements = 1 << 18;

enum class Kind
{
  Float,
  Signed,
  Unsigned
};

struct NpyHeader
{
  int Major = 0;
  int Minor = 0;
  std::string Descr;
  Kind ElementKind = Kind::Float;
  int ItemSize = 0;
  bool Swap = false; // file byte order differs from the host's
  bool FortranOrder = false;
  std::vector<long long> Shape;
  long long DataOffset = 0;
  int Dims[2] = { 0, 0 }; // numpy axis 0 and axis 1 lengths (axis 1 is 1 for a 1-D array)
};

bool HostIsLittleEndian()
{
  const uint16_t probe = 1;
  unsigned char b[2];
  std::memcpy(b, &probe, 2);
  return b[0] == 1;
}

/// A minimal reader of the Python literal dict in the .npy header: string keys, and values that
/// are strings, True/False, or tuples of integers; anything else is skipped with brackets matched.
class DictParser
{
public:
  explicit DictParser(const std::string& text)
    : Text(text)
  {
  }

  bool Parse(NpyHeader& h, std::string& error)
  {
    bool haveDescr = false;
    bool haveOrder = false;
    bool haveShape = false;
    this->SkipSpace();
    if (!this->Accept('{'))
    {
      error = "header is not a Python dict (no '{')";
      return false;
    }
    while (true)
    {
      this->SkipSpace();
      if (this->Accept('}'))
      {
        break;
      }
      std::string key;
      if (!this->ParseString(key))
      {
        error = "header dict key is not a quoted string";
        return false;
      }
      this->SkipSpace();
      if (!this->Accept(':'))
      {
        error = "header dict has no ':' after key '" + key + "'";
        return false;
      }
      this->SkipSpace();
      if (key == "descr")
      {
        if (this->Peek() == '[')
        {
          error = "structured dtypes (a list 'descr') are not supported";
          return false;
        }
        if (!this->ParseString(h.Descr))
        {
          error = "'descr' is not a string";
          return false;
        }
        haveDescr = true;
      }
      else if (key == "fortran_order")
      {
        if (this->AcceptWord("True"))
        {
          h.FortranOrder = true;
        }
        else if (this->AcceptWord("False"))
        {
          h.FortranOrder = false;
        }
        else
        {
          error = "'fortran_order' is neither True nor False";
          return false;
        }
        haveOrder = true;
      }
      else if (key == "shape")
      {
        if (!this->ParseShape(h.Shape))
        {
          error = "'shape' is not a tuple of non-negative integers";
          return false;
        }
        haveShape = true;
      }
      else if (!this->SkipValue())
      {
        error = "cannot parse the value of header key '" + key + "'";
        return false;
      }
      this->SkipSpace();
      if (this->Accept(','))
      {
        continue;
      }
      if (this->Accept('}'))
      {
        break;
      }
      error = "header dict entries are not separated by ','";
      return false;
    }
    if (!haveDescr || !haveOrder || !haveShape)
    {
      error = "header lacks 'descr', 'fortran_order' or 'shape'";
      return false;
    }
    return true;
  }

private:
  char Peek() const { return this->Pos < this->Text.size() ? this->Text[this->Pos] : '\0'; }

  bool Accept(char c)
  {
    if (this->Peek() == c && this->Pos < this->Text.size())
    {
      ++this->Pos;
      return true;
    }
    return false;
  }

  bool AcceptWord(const char* word)
  {
    const size_t n = std::strlen(word);
    if (this->Text.compare(this->Pos, n, word) == 0)
    {
      const size_t end = this->Pos + n;
      if (end < this->Text.size() &&
          (std::isalnum(static_cast<unsigned char>(this->Text[end])) || this->Text[end] == '_'))
      {
        return false;
      }
      this->Pos = end;
      return true;
    }
    return false;
  }

  void SkipSpace()
  {
    while (this->Pos < this->Text.size() &&
           std::isspace(static_cast<unsigned char>(this->Text[this->Pos])))
    {
      ++this->Pos;
    }
  }

  bool ParseString(std::string& out)
  {
    const char quote = this->Peek();
    if (quote != '\'' && quote != '"')
    {
      return false;
    }
    ++this->Pos;
    out.clear();
    while (this->Pos < this->Text.size() && this->Text[this->Pos] != quote)
    {
      if (this->Text[this->Pos] == '\\' && this->Pos + 1 < this->Text.size())
      {
        ++this->Pos;
      }
      out += this->Text[this->Pos++];
    }
    return this->Accept(quote);
  }

  bool ParseShape(std::vector<long long>& shape)
  {
    shape.clear();
    if (!this->Accept('('))
    {
      return false;
    }
    while (true)
    {
      this->SkipSpace();
      if (this->Accept(')'))
      {
        return true;
      }
      if (!std::isdigit(static_cast<unsigned char>(this->Peek())))
      {
        return false;
      }
      long long v = 0;
      while (std::isdigit(static_cast<unsigned char>(this->Peek())))
      {
        v = v * 10 + (this->Text[this->Pos++] - '0');
        if (v > (1LL << 40)) // far beyond MaxNodes already; stops overflow
        {
          return false;
        }
      }
      this->Accept('L'); // Python 2 long suffix, written by old numpy
      shape.push_back(v);
      this->SkipSpace();
      if (this->Accept(')'))
      {
        return true;
      }
      if (!this->Accept(','))
      {
        return false;
      }
    }
  }

  /// Skips a string, a word/number, or a bracketed value with nesting.
  bool SkipValue()
  {
    const char c = this->Peek();
    if (c == '\'' || c == '"')
    {
      std::string ignored;
      return this->ParseString(ignored);
    }
    if (c == '(' || c == '[' || c == '{')
    {
      int depth = 0;
      while (this->Pos < this->Text.size())
      {
        const char d = this->Text[this->Pos];
        if (d == '\'' || d == '"')
        {
          std::string ignored;
          if (!this->ParseString(ignored))
          {
            return false;
          }
          continue;
        }
        ++this->Pos;
        if (d == '(' || d == '[' || d == '{')
        {
          ++depth;
        }
        else if (d == ')' || d == ']' || d == '}')
        {
          if (--depth == 0)
          {
            return true;
          }
        }
      }
      return false;
    }
    const size_t start = this->Pos;
    while (
      this->Pos < this->Text.size() && this->Text[this->Pos] != ',' && this->Text[this->Pos] != '}')
    {
      ++this->Pos;
    }
    return this->Pos > start;
  }

  const std::string& Text;
  size_t Pos = 0;
};

/// Interprets 'descr' (e.g. "<f8"); fills kind, item size and whether bytes must be swapped.
bool ParseDescr(NpyHeader& h, std::string& error)
{
  const std::string& d = h.Descr;
  if (d.size() < 3 || std::string("<>|=").find(d[0]) == std::string::npos)
  {
    error = "unsupported dtype '" + d + "'";
    return false;
  }
  const std::string sizeText = d.substr(2);
  if (sizeText.empty() || sizeText.size() > 2 ||
      !std::all_of(sizeText.begin(),
        sizeText.end(),
        [](char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }))
  {
    error = "unsupported dtype '" + d + "'";
    return false;
  }
  h.ItemSize = std::stoi(sizeText);
  const char kind = d[1];
  bool ok = false;
  if (kind == 'f')
  {
    h.ElementKind = Kind::Float;
    ok = h.ItemSize == 4 || h.ItemSize == 8;
  }
  else if (kind == 'i' || kind == 'u')
  {
    h.ElementKind = kind == 'i' ? Kind::Signed : Kind::Unsigned;
    ok = h.ItemSize == 1 || h.ItemSize == 2 || h.ItemSize == 4 || h.ItemSize == 8;
  }
  if (!ok)
  {
    error = "unsupported dtype '" + d + "' (supported: float32/64, int8/16/32/64, uint8/16/32/64)";
    return false;
  }
  const bool fileLittle = d[0] == '<' || (d[0] == '=' && HostIsLittleEndian()) || d[0] == '|';
  h.Swap = h.ItemSize > 1 && fileLittle != HostIsLittleEndian();
  return true;
}

/// Reads the preamble and header of an open file of known size.
bool ReadHeader(std::istream& in, long long fileSize, NpyHeader& h, std::string& error)
{
  unsigned char pre[12];
  if (fileSize < 10 || !in.read(reinterpret_cast<char*>(pre), 10))
  {
    error = "file is too short for a .npy preamble";
    return false;
  }
  if (std::memcmp(pre, "\x93NUMPY", 6) != 0)
  {
    error = "no .npy magic string (\\x93NUMPY) at the start";
    return false;
  }
  h.Major = pre[6];
  h.Minor = pre[7];
  long long headerLength = 0;
  long long preamble = 10;
  if (h.Major == 1)
  {
    headerLength = pre[8] | (pre[9] << 8);
  }
  else if (h.Major == 2 || h.Major == 3)
  {
    if (fileSize < 12 || !in.read(reinterpret_cast<char*>(pre + 10), 2))
    {
      error = "file is too short for a version 2/3 .npy preamble";
      return false;
    }
    headerLength = static_cast<long long>(pre[8]) | (static_cast<long long>(pre[9]) << 8) |
                   (static_cast<long long>(pre[10]) << 16) |
                   (static_cast<long long>(pre[11]) << 24);
    preamble = 12;
  }
  else
  {
    std::ostringstream msg;
    msg << "unsupported .npy format version " << h.Major << "." << h.Minor
        << " (supported: 1.0, 2.0, 3.0)";
    error = msg.str();
    return false;
  }
  if (headerLength <= 0 || headerLength > MaxHeaderLength || preamble + headerLength > fileSize)
  {
    std::ostringstream msg;
    msg << "header length " << headerLength << " does not fit the file (" << fileSize << " bytes)";
    error = msg.str();
    return false;
  }
  std::string text(static_cast<size_t>(headerLength), '\0');
  if (!in.read(&text[0], static_cast<std::streamsize>(headerLength)))
  {
    error = "cannot read the header";
    return false;
  }
  h.DataOffset = preamble + headerLength;

  DictParser parser(text);
  if (!parser.Parse(h, error) || !ParseDescr(h, error))
  {
    return false;
  }

  // (n,) and (rows, cols) are grids, and so is (rows, cols, 1), which image stacks often are.
  const size_t axes = h.Shape.size();
  if (axes == 0 || axes > 3 || (axes == 3 && h.Shape[2] != 1))
  {
    std::ostringstream msg;
    msg << "shape (";
    for (size_t a = 0; a < axes; ++a)
    {
      msg << (a ? ", " : "") << h.Shape[a];
    }
    msg << ") is not a grid: need (n,), (rows, cols) or (rows, cols, 1)";
    error = msg.str();
    return false;
  }
  const long long d0 = h.Shape[0];
  const long long d1 = axes > 1 ? h.Shape[1] : 1;
  // Each factor is bounded first: shape values up to 2^40 multiply past 2^63.
  if (d0 <= 0 || d1 <= 0 || d0 > MaxNodes || d1 > MaxNodes || d0 > MaxNodes / d1)
  {
    std::ostringstream msg;
    msg << "absurd grid dimensions in 'shape': " << d0 << " x " << d1
        << " (need 0 < n < 2^31 nodes)";
    error = msg.str();
    return false;
  }
  h.Dims[0] = static_cast<int>(d0);
  h.Dims[1] = static_cast<int>(d1);
  const long long dataBytes = d0 * d1 * h.ItemSize;
  if (fileSize - h.DataOffset < dataBytes)
  {
    std::ostringstream msg;
    msg << "file truncated: " << d0 << " x " << d1 << " values of " << h.ItemSize << " bytes need "
        << dataBytes << " bytes after the header, only " << (fileSize - h.DataOffset) << " remain";
    error = msg.str();
    return false;
  }
  return true;
}

/// Opens a file and measures it; errors are phrased for the user.
bool OpenFile(const char* fileName, vtksys::ifstream& in, long long& size, std::string& error)
{
  if (!fileName || !*fileName)
  {
    error = "no file name set";
    return false;
  }
  if (!vtksys::SystemTools::FileExists(fileName, /*isFile=*/true))
  {
    error = "file does not exist or is not a regular file";
    return false;
  }
  in.open(fileName, std::ios::in | std::ios::binary);
  if (!in)
  {
    error = "cannot open file";
    return false;
  }
  in.seekg(0, std::ios::end);
  size = static_cast<long long>(in.tellg());
  in.seekg(0, std::ios::beg);
  if (size < 0 || !in)
  {
    error = "cannot determine the file size";
    return false;
  }
  return true;
}

template<typename TIn, typename TOut>
TOut LoadElement(const unsigned char* src, bool swap)
{
  unsigned char b[sizeof(TIn)];
  if (swap)
  {
    std::reverse_copy(src, src + sizeof(TIn), b);
  }
  else
  {
    std::memcpy(b, src, sizeof(TIn));
  }
  TIn v;
  std::memcpy(&v, b, sizeof(TIn));
  return static_cast<TOut>(v);
}

/// Converts `n` file elements starting at file index `first` into `dst`, placing file element k
/// at output index k (identity) or, for a transposed layout of P x Q (k = p * Q + q), at p + q * P.
template<typename TIn, typename TOut>
vtkIdType ConvertChunk(const unsigned char* src,
  vtkIdType first,
  vtkIdType n,
  bool swap,
  bool transpose,
  vtkIdType P,
  vtkIdType Q,
  bool hasNull,
  TOut nullValue,
  TOut* dst)
{
  const TOut nan = std::numeric_limits<TOut>::quiet_NaN();
  vtkIdType noData = 0;
  vtkIdType p = transpose ? first / Q : 0;
  vtkIdType q = transpose ? first % Q : 0;
  for (vtkIdType k = 0; k < n; ++k)
  {
    TOut v = LoadElement<TIn, TOut>(src + k * sizeof(TIn), swap);
    if (std::isnan(v) || (hasNull && v == nullValue))
    {
      v = nan;
      ++noData;
    }
    if (transpose)
    {
      dst[p + q * P] = v;
      if (++q == Q)
      {
        q = 0;
        ++p;
      }
    }
    else
    {
      dst[first + k] = v;
    }
  }
  return noData;
}

template<typename TOut>
vtkIdType ConvertAny(const NpyHeader& h,
  const unsigned char* src,
  vtkIdType first,
  vtkIdType n,
  bool transpose,
  vtkIdType P,
  vtkIdType Q,
  bool hasNull,
  TOut nullValue,
  TOut* dst)
{
#define strataConvert(TIn)                                                                         \
  return ConvertChunk<TIn, TOut>(src, first, n, h.Swap, transpose, P, Q, hasNull, nullValue, dst)
  switch (h.ElementKind)
  {
    case Kind::Float:
      if (h.ItemSize == 4)
      {
        strataConvert(float);
      }
      strataConvert(double);
    case Kind::Signed:
      switch (h.ItemSize)
      {
        case 1:
          strataConvert(int8_t);
        case 2:
          strataConvert(int16_t);
        case 4:
          strataConvert(int32_t);
        default:
          strataConvert(int64_t);
      }
    case Kind::Unsigned:
      switch (h.ItemSize)
      {
        case 1:
          strataConvert(uint8_t);
        case 2:
          strataConvert(uint16_t);
        case 4:
          strataConvert(uint32_t);
        default:
          strataConvert(uint64_t);
      }
  }
#undef strataConvert
  return 0;
}

/// How the file's elements land in the image: element k of the file is at numpy index (a0, a1)
/// with k = a0 + a1 * d0 (Fortran order) or k = a0 * d1 + a1 (C order). The image puts (ix, iy)
/// at ix + iy * nx with ix = a0 (a1 when swapped), so exactly one of "Fortran order" and
/// "swapped" makes the copy an identity, and otherwise it is a transpose of a P x Q row-major
/// block.
struct Layout
{
  bool Transpose = false;
  vtkIdType P = 0;
  vtkIdType Q = 0;

  Layout(const NpyHeader& h, bool swapAxes)
    : Transpose(h.FortranOrder == swapAxes)
    , P(h.FortranOrder ? h.Dims[1] : h.Dims[0])
    , Q(h.FortranOrder ? h.Dims[0] : h.Dims[1])
  {
  }
};

/// Reads the values of the stream `in` (at the header's data offset) into `values` (float, or
/// double for float64 files), in chunks, converting and placing them; `noData` counts the
/// holes (NaN and `nullValue`, compared after conversion).
bool ReadValues(std::istream& in,
  const NpyHeader& h,
  bool swapAxes,
  double nullValue,
  const std::function<void(double)>& progress,
  vtkDataArray* values,
  vtkIdType& noData,
  std::string& error)
{
  const Layout layout(h, swapAxes);
  const vtkIdType total = static_cast<vtkIdType>(h.Dims[0]) * h.Dims[1];
  const bool hasNull = !std::isnan(nullValue);
  std::vector<unsigned char> buffer(static_cast<size_t>(ChunkElements) * h.ItemSize);
  in.seekg(h.DataOffset, std::ios::beg);
  noData = 0;
  for (vtkIdType first = 0; first < total; first += ChunkElements)
  {
    const vtkIdType n = std::min(ChunkElements, total - first);
    if (!in.read(
          reinterpret_cast<char*>(buffer.data()), static_cast<std::streamsize>(n * h.ItemSize)))
    {
      std::ostringstream msg;
      msg << "read error after " << first << " of " << total << " values";
      error = msg.str();
      return false;
    }
    if (auto* d = vtkDoubleArray::SafeDownCast(values))
    {
      noData += ConvertAny<double>(h,
        buffer.data(),
        first,
        n,
        layout.Transpose,
        layout.P,
        layout.Q,
        hasNull,
        nullValue,
        d->GetPointer(0));
    }
    else
    {
      noData += ConvertAny<float>(h,
        buffer.data(),
        first,
        n,
        layout.Transpose,
        layout.P,
        layout.Q,
        hasNull,
        static_cast<float>(nullValue),
        vtkFloatArray::SafeDownCast(values)->GetPointer(0));
    }
    progress(static_cast<double>(first + n) / total);
  }
  return true;
}
}

//------------------------------------------------------------------------------
class vtkNumpyGridReader::vtkInternals
{
public:
  NpyHeader Header;
  bool Valid = false;

  /// Image dimensions after the axis convention.
  int NX() const { return this->Header.Dims[this->Swapped ? 1 : 0]; }
  int NY() const { return this->Header.Dims[this->Swapped ? 0 : 1]; }
  bool Swapped = false;
};

//------------------------------------------------------------------------------
vtkNumpyGridReader::vtkNumpyGridReader()
  : Internals(new vtkInternals)
{
}

//------------------------------------------------------------------------------
vtkNumpyGridReader::~vtkNumpyGridReader() = default;

//------------------------------------------------------------------------------
bool vtkNumpyGridReader::CanReadFile(const char* fileName)
{
  vtksys::ifstream in;
  long long size = 0;
  std::string error;
  char magic[6];
  return OpenFile(fileName, in, size, error) && size >= 10 && in.read(magic, 6) &&
         std::memcmp(magic, "\x93NUMPY", 6) == 0;
}

//------------------------------------------------------------------------------
int vtkNumpyGridReader::GetMajorVersion() const
{
  return this->Internals->Valid ? this->Internals->Header.Major : 0;
}

int vtkNumpyGridReader::GetMinorVersion() const
{
  return this->Internals->Valid ? this->Internals->Header.Minor : 0;
}

const char* vtkNumpyGridReader::GetDescr() const
{
  return this->Internals->Valid ? this->Internals->Header.Descr.c_str() : "";
}

bool vtkNumpyGridReader::GetFortranOrder() const
{
  return this->Internals->Valid && this->Internals->Header.FortranOrder;
}

int vtkNumpyGridReader::GetNumberOfAxes() const
{
  return this->Internals->Valid ? static_cast<int>(this->Internals->Header.Shape.size()) : 0;
}

vtkIdType vtkNumpyGridReader::GetShape(int axis) const
{
  const auto& shape = this->Internals->Header.Shape;
  return this->Internals->Valid && axis >= 0 && axis < static_cast<int>(shape.size())
           ? static_cast<vtkIdType>(shape[axis])
           : 0;
}

int vtkNumpyGridReader::GetOutputDataType() const
{
  if (!this->Internals->Valid)
  {
    return 0;
  }
  const NpyHeader& h = this->Internals->Header;
  return h.ElementKind == Kind::Float && h.ItemSize == 8 ? VTK_DOUBLE : VTK_FLOAT;
}

//------------------------------------------------------------------------------
void vtkNumpyGridReader::ResetResults()
{
  this->Superclass::ResetResults();
  this->Internals->Valid = false;
  this->Internals->Header = NpyHeader();
}

//------------------------------------------------------------------------------
bool vtkNumpyGridReader::ReadGridInformation(std::string& error)
{
  vtkInternals& internals = *this->Internals;
  vtksys::ifstream in;
  long long size = 0;
  if (!OpenFile(this->FileName, in, size, error) || !ReadHeader(in, size, internals.Header, error))
  {
    return false;
  }
  internals.Valid = true;
  internals.Swapped = this->SwapAxes;
  this->NX = internals.NX();
  this->NY = internals.NY();
  std::copy(this->Origin, this->Origin + 2, this->GridOrigin);
  std::copy(this->Spacing, this->Spacing + 2, this->GridSpacing);
  this->GridRotation = this->Rotation;
  return true;
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkDataArray> vtkNumpyGridReader::ReadGridValues(std::string& error)
{
  this->NumberOfNoDataValues = 0;
  // Re-read the header from the stream the values come from; the file may have changed since
  // the information pass.
  vtksys::ifstream in;
  long long size = 0;
  NpyHeader h;
  if (!OpenFile(this->FileName, in, size, error) || !ReadHeader(in, size, h, error))
  {
    return nullptr;
  }
  const NpyHeader& known = this->Internals->Header;
  if (!this->Internals->Valid || h.Dims[0] != known.Dims[0] || h.Dims[1] != known.Dims[1] ||
      h.Descr != known.Descr || this->SwapAxes != this->Internals->Swapped)
  {
    error = "the file or the axis setting changed since the information pass";
    return nullptr;
  }
  const vtkIdType total = static_cast<vtkIdType>(h.Dims[0]) * h.Dims[1];
  vtkSmartPointer<vtkDataArray> values = NewValues(this->GetOutputDataType(), total, error);
  if (!values)
  {
    return nullptr;
  }
  vtkIdType noData = 0;
  this->UpdateProgress(0.0);
  if (!ReadValues(
        in,
        h,
        this->SwapAxes,
        this->NullValue,
        [this](double fraction) { this->UpdateProgress(fraction); },
        values,
        noData,
        error))
  {
    return nullptr;
  }
  std::copy(this->Origin, this->Origin + 2, this->GridOrigin);
  std::copy(this->Spacing, this->Spacing + 2, this->GridSpacing);
  this->GridRotation = this->Rotation;
  this->NumberOfNoDataValues = noData;
  return values;
}

//------------------------------------------------------------------------------
void vtkNumpyGridReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Origin: " << this->Origin[0] << " " << this->Origin[1] << "\n";
  os << indent << "Spacing: " << this->Spacing[0] << " " << this->Spacing[1] << "\n";
  os << indent << "Rotation: " << this->Rotation << "\n";
  os << indent << "SwapAxes: " << (this->SwapAxes ? "On" : "Off") << "\n";
  const vtkInternals& internals = *this->Internals;
  os << indent << "HeaderValid: " << (internals.Valid ? "yes" : "no") << "\n";
  os << indent << "Version: " << internals.Header.Major << "." << internals.Header.Minor << "\n";
  os << indent << "Descr: " << internals.Header.Descr << "\n";
  os << indent << "FortranOrder: " << (internals.Header.FortranOrder ? "True" : "False") << "\n";
  os << indent << "Shape: (";
  for (size_t a = 0; a < internals.Header.Shape.size(); ++a)
  {
    os << (a ? ", " : "") << internals.Header.Shape[a];
  }
  os << ")\n";
  os << indent << "DataOffset: " << internals.Header.DataOffset << "\n";
  os << indent << "Dimensions: " << (internals.Valid ? internals.NX() : 0) << " x "
     << (internals.Valid ? internals.NY() : 0) << "\n";
}
