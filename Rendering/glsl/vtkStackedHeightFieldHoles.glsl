// NaN and holes are tested on the bits and by magnitude, never by isnan or a comparison that only
// NaN fails: fast math may assume there is no NaN and fold those away (on NVIDIA it did).
// Which of four values are NaN (exponent all ones, mantissa not zero).
bvec4 strataIsNaN(vec4 v)
{
  return greaterThan(floatBitsToUint(v) & uvec4(0x7fffffffu), uvec4(0x7f800000u));
}

// Which of four heights are holes: NaN in core (strata::HeightFieldStack), BIG where a paged tile is
// missing, and, as on the CPU, every height of magnitude 1e30 or more (Inf among them, by its
// bits: exponent all ones).
bvec4 strataHoles(vec4 h)
{
  uvec4 exponent = floatBitsToUint(h) & uvec4(0x7f800000u);
  uvec4 notFinite = uvec4(equal(exponent, uvec4(0x7f800000u)));
  return bvec4(max(notFinite, uvec4(greaterThanEqual(abs(h), vec4(1.0e30)))));
}
