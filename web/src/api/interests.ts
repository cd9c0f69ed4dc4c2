import type { CityDetail, LayoutParams } from './types';

/** A POI category of a city with how many POIs it has (GET /cities/{id} `categories`). */
export interface CityCategory {
  id: string;
  count: number;
}

/** A tourist's weight per category; a category left out weighs 1 (the server's default). */
export type InterestWeights = Record<string, number>;

/**
 * Layout parameters with the tourist's interests: `interests` is the `interests` query value
 * (`category:weight,...`), absent for the default layout. Where it is set, the layout, the
 * clusters, the heat map and the map files follow it (api/openapi.yaml, parameter Interests).
 */
export type InterestParams = LayoutParams & { interests?: string };

/** The city's categories, most frequent first (then by name); [] from an older server without them. */
export function cityCategories(city: CityDetail): CityCategory[] {
  const categories = (city as CityDetail & { categories?: CityCategory[] }).categories ?? [];
  return [...categories].sort((a, b) => b.count - a.count || a.id.localeCompare(b.id));
}

/**
 * The `interests` query value of `weights`: the categories not at 1, sorted by name, or ''
 * when every category is at 1 (the default layout). A name holding a comma cannot be sent in
 * a query (the server splits on commas): it is left out, so it keeps weight 1.
 */
export function interestsQuery(weights: InterestWeights): string {
  return Object.entries(weights)
    .filter(([name, weight]) => weight !== 1 && !name.includes(','))
    .sort(([a], [b]) => a.localeCompare(b))
    .map(([name, weight]) => `${name}:${weight}`)
    .join(',');
}
