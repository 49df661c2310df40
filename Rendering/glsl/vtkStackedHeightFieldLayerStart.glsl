// Peel k: this ray starts just behind layer k - 1 (its stored depth a few float32 steps on,
  // taken back to a ray parameter, then the tie tolerance); no layer k - 1, no layer k.
  ivec2 peelPixel = ivec2(gl_FragCoord.xy);
  float peelScene = texelFetch(uPeelScene, peelPixel, 0).r;
  if (uPeelLayer > 0)
  {
    float previous = texelFetch(uPeelPrevious, peelPixel, 0).r;
    if (previous >= 1.0)
    {
      discard;
    }
    float behind = min(previous + 2.5e-7, 1.0);
    float zNdc = (2.0 * behind - gl_DepthRange.near - gl_DepthRange.far) / gl_DepthRange.diff;
    vec4 p4 = uClipToGrid * vec4(ndc, zNdc, 1.0);
    tEnter = max(tEnter, dot(p4.xyz / p4.w - o, d) / dot(d, d) + uTieEps);
  }
