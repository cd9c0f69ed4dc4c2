/**
 * Only web links: the data comes from imported files and must not smuggle in javascript:,
 * data: or other URLs. The normalised http(s) URL, or undefined for anything else.
 */
export function httpUrl(value: string | undefined): string | undefined {
  if (!value) return undefined;
  try {
    const url = new URL(value);
    return url.protocol === 'http:' || url.protocol === 'https:' ? url.href : undefined;
  } catch {
    return undefined;
  }
}
