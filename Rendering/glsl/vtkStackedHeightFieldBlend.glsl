// The renderer's translucent pass (VTK's vtkOrderIndependentTranslucentPass), without a volume
  // ray caster: the stack's translucent hits in front of its first opaque one, composited front
  // to back (up to 8 layers, coincident ones merged) into one fragment at the first one's depth,
  // written as that pass accumulates: premultiplied colour and opacity, and the opacity.
  vec4 blended = vec4(0.0);
  for (int k = 0; k < 8; ++k)
  {
    vec4 c = strataShade(hitLayer, hitCell, o + tHit * d);
    blended += (1.0 - blended.a) * vec4(c.rgb * c.a, c.a);
    if (!strataCast(o, d, tHit + 16.0 * uTieEps, tExit, tHit, hitLayer, hitCell) ||
      strataHorizonOpacity(hitLayer) >= 1.0)
    {
      break;
    }
  }
  gl_FragData[0] = blended;
  gl_FragData[1] = vec4(blended.a);
