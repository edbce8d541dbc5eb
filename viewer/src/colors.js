// Fixed colours of the viewer (issue #25 viewer contract, docs/viewer.md "What the page shows"):
// verdict colours for regions, witnesses and curves; legend colours come from the document.
export const VERDICT_COLORS = {
  clash: 0xe02020,
  contact: 0xf0a020,
  clearance: 0x2060e0,
  undecided: 0xd020d0,
};
export const CURVE_COLOR = 0xffd400;
export const CURVE_OUTLINE_COLOR = 0x000000;
export const WITNESS_COLOR = 0x2060e0;
export const BODY_OPACITY = 0.35;
export const BACKGROUND_COLOR = 0xf4f5f7;

/** The colour of a verdict (unknown verdicts draw as undecided). */
export function verdictColor(verdict) {
  return VERDICT_COLORS[verdict] ?? VERDICT_COLORS.undecided;
}

/** [r,g,b] in 0..1 -> 0xrrggbb. */
export function rgbToHex(rgb) {
  const c = (v) => Math.max(0, Math.min(255, Math.round(v * 255)));
  return (c(rgb[0]) << 16) | (c(rgb[1]) << 8) | c(rgb[2]);
}

/** 0xrrggbb -> "#rrggbb". */
export function hexToCss(hex) {
  return '#' + hex.toString(16).padStart(6, '0');
}
