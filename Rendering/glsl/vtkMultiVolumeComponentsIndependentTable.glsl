tf = textureLod(uTransfer@n@@c@, vec2((s[@i@] - uTableRange@n@@c@.x) * uTableRange@n@@c@.y + uTableRange@n@@c@.z, 0.5), 0.0);
  weighted += uWeights@n@[@i@] * tf.a;
  squares += uWeights@n@[@i@] > 0.0 ? tf.a * tf.a : 0.0;
  e += uWeights@n@[@i@] * tf.a * tf.rgb;
  
