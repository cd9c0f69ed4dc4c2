import type { CrowdAttribution } from '../api/types';
import { h } from '../ui/dom';

/** The models a credit covers: its "model" may name several ("Horse, Donkey, Cow"). */
export const creditedModels = (credit: CrowdAttribution) => credit.model.split(',').map((name) => name.trim());

/** The credits of the models a scene shows (each with a link to its source where there is one). */
export function showModelCredits(box: HTMLElement, attribution: CrowdAttribution[], models: string[]): void {
  const used = attribution.filter((credit) => creditedModels(credit).some((model) => models.includes(model)));
  box.replaceChildren(
    ...used.map((credit) =>
      h(
        'p',
        { 'data-model': credit.model },
        credit.text,
        credit.url && /^https?:\/\//.test(credit.url) ? ' · ' : null,
        credit.url && /^https?:\/\//.test(credit.url) ? h('a', { href: credit.url, target: '_blank', rel: 'noopener noreferrer' }, 'source') : null,
      ),
    ),
  );
  box.hidden = box.childElementCount === 0;
}
