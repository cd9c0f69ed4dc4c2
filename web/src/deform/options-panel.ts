import type { GridOption } from '../api/types';
import { h } from '../ui/dom';

export interface DeformOptions {
  grid: GridOption;
  solver: 'cholesky' | 'cg';
  relax: boolean;
  showGrid: boolean;
  showOriginal: boolean;
}

const DEFAULTS = { base: 10, depth: 3, c: 4, n: 80 };

/** A number box; what it holds goes to the server as typed (the server names a bad field). */
function numberInput(id: string, value: number, min: number, max?: number): HTMLInputElement {
  return h('input', { type: 'number', id, value, min, max, step: 1, class: 'number-input', 'data-testid': id });
}

function readNumber(input: HTMLInputElement, fallback: number): number {
  return input.value.trim() === '' ? fallback : Number(input.value);
}

/** Grid, solver and display options of the Deform view. */
export class OptionsPanel {
  readonly element: HTMLElement;
  private readonly kind: HTMLSelectElement;
  private readonly base = numberInput('grid-base', DEFAULTS.base, 1, 64);
  private readonly depth = numberInput('grid-depth', DEFAULTS.depth, 0, 6);
  private readonly c = numberInput('grid-c', DEFAULTS.c, 0);
  private readonly n = numberInput('grid-n', DEFAULTS.n, 1, 256);
  private readonly adaptiveFields: HTMLElement;
  private readonly uniformFields: HTMLElement;
  private readonly solver: HTMLSelectElement;
  private readonly relax: HTMLInputElement;
  private readonly showGrid: HTMLInputElement;
  private readonly showOriginal: HTMLInputElement;

  constructor(onChange: () => void) {
    this.kind = h(
      'select',
      { id: 'grid-kind', 'data-testid': 'grid-kind' },
      h('option', { value: 'adaptive' }, 'Adaptive (quadtree)'),
      h('option', { value: 'uniform' }, 'Uniform'),
      h('option', { value: 'edges' }, 'Road edges (no grid)'),
    );
    this.solver = h(
      'select',
      { id: 'solver', 'data-testid': 'solver' },
      h('option', { value: 'cholesky' }, 'Cholesky (cached)'),
      h('option', { value: 'cg' }, 'Conjugate gradients'),
    );
    this.relax = h('input', { type: 'checkbox', 'data-testid': 'relax' });
    this.relax.checked = true;  // the server's default too: no folded grid cell drawn
    this.showGrid = h('input', { type: 'checkbox', 'data-testid': 'show-grid' });
    this.showOriginal = h('input', { type: 'checkbox', 'data-testid': 'show-original' });
    const field = (labelText: string, input: HTMLElement, title?: string) =>
      h('label', { class: 'inline-field', title }, labelText, input);
    this.adaptiveFields = h(
      'div',
      { class: 'option-group' },
      field('Base cells', this.base, 'Cells along the longer side of the coarsest grid'),
      field('Depth', this.depth, 'Quadtree levels below the base grid'),
      field('Split above c', this.c, 'Split a cell holding more than c road vertices'),
    );
    this.uniformFields = h('div', { class: 'option-group' }, field('Cells n', this.n, 'Cells along the longer side'));
    // What a traveller uses stays in view; how the map is computed goes behind "Advanced"
    // (closed until opened), for those who want to compare grids and solvers.
    this.element = h(
      'div',
      { class: 'options' },
      h('label', { class: 'check' }, this.showOriginal, 'Show the roads as they really lie'),
      h(
        'details',
        { class: 'advanced', 'data-testid': 'deform-advanced' },
        h('summary', {}, 'Advanced: grid and solver'),
        h('label', { class: 'inline-field', for: 'grid-kind' }, 'Grid', this.kind),
        this.adaptiveFields,
        this.uniformFields,
        h('label', { class: 'inline-field', for: 'solver' }, 'Solver', this.solver),
        h('label', { class: 'check' }, this.relax, 'Relax fold-overs after solving'),
        h('label', { class: 'check' }, this.showGrid, 'Show the deformed grid'),
      ),
    );
    for (const input of [this.kind, this.base, this.depth, this.c, this.n, this.solver, this.relax, this.showGrid, this.showOriginal]) {
      input.addEventListener('change', () => {
        this.syncFields();
        onChange();
      });
    }
    this.syncFields();
  }

  get value(): DeformOptions {
    const kind = this.kind.value;
    const grid: GridOption =
      kind === 'uniform'
        ? { kind: 'uniform', n: readNumber(this.n, DEFAULTS.n) }
        : kind === 'edges'
          ? { kind: 'edges' }
          : {
              kind: 'adaptive',
              base: readNumber(this.base, DEFAULTS.base),
              depth: readNumber(this.depth, DEFAULTS.depth),
              c: readNumber(this.c, DEFAULTS.c),
            };
    return {
      grid,
      solver: this.solver.value === 'cg' ? 'cg' : 'cholesky',
      relax: this.relax.checked,
      showGrid: this.showGrid.checked,
      showOriginal: this.showOriginal.checked,
    };
  }

  private syncFields(): void {
    this.adaptiveFields.hidden = this.kind.value !== 'adaptive';
    this.uniformFields.hidden = this.kind.value !== 'uniform';
  }
}
