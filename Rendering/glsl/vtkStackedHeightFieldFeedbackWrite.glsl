// The footprint is one pixel unprojected at the hit's depth, in level-0 cells.
  // Texels of the renderer's viewport (the buffer is sized to it), not of the window.
  ivec2 feedbackPixel = ivec2(gl_FragCoord.xy - uViewport.xy);
  if (all(equal(feedbackPixel % uFeedbackScale, uFeedbackOffset)))
  {
    vec3 n0 = clip.xyz / clip.w;
    vec4 gx = uClipToGrid * vec4(n0 + vec3(2.0 / uViewport.z, 0.0, 0.0), 1.0);
    vec4 gy = uClipToGrid * vec4(n0 + vec3(0.0, 2.0 / uViewport.w, 0.0), 1.0);
    float footprint = max(length(gx.xy / gx.w - pGrid.xy), length(gy.xy / gy.w - pGrid.xy)) * uLodScale;
    // Clamped in float: footprint is Inf near the eye plane, and int(Inf) is undefined.
    int want = int(clamp(floor(log2(max(footprint, 1.0))), 0.0, float(uPageLevels - 1)));
    ivec2 tile = min(max(ivec2(floor(pGrid.xy)), ivec2(0)) / uPageStride, uPageTiles - 1) >> want;
    uint id = strataPackPage(uint(hitLayer), uint(want), uint(tile.y * uLevelTilesX[want] + tile.x));
    imageStore(uFeedback, feedbackPixel / uFeedbackScale, uvec4(id, 0u, 0u, 0u));
  }
