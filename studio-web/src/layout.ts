// The workspace layout: the tabs over the right area and the resizable splitters.

const LAYOUT_KEY = "matloom-studio-layout";

function notifyResize(): void {
  window.dispatchEvent(new Event("resize"));
}

/** Show one tab of the right area: viewer, inspector, compare, export or author. */
export function showTab(name: string): void {
  for (const b of document.querySelectorAll<HTMLButtonElement>("#tabs [data-tab]")) {
    const on = b.dataset.tab === name;
    b.setAttribute("aria-selected", String(on));
    b.tabIndex = on ? 0 : -1;
  }
  for (const p of document.querySelectorAll<HTMLElement>(".tab-pane")) p.hidden = p.dataset.pane !== name;
  notifyResize();
}

function mountTabs(): void {
  const buttons = [...document.querySelectorAll<HTMLButtonElement>("#tabs [data-tab]")];
  for (const b of buttons) {
    b.addEventListener("click", () => showTab(b.dataset.tab ?? "viewer"));
    b.addEventListener("keydown", (e) => {
      const k = buttons.indexOf(b);
      const next = e.key === "ArrowRight" ? k + 1 : e.key === "ArrowLeft" ? k - 1 : -2;
      if (next === -2) return;
      const target = buttons[(next + buttons.length) % buttons.length];
      target.focus();
      showTab(target.dataset.tab ?? "viewer");
    });
  }
}

function mountSplitters(): void {
  const work = document.getElementById("work");
  if (!work) return;
  try {
    const saved = JSON.parse(localStorage.getItem(LAYOUT_KEY) ?? "{}") as Record<string, string>;
    for (const [k, v] of Object.entries(saved)) if (/^\d+px$/.test(v)) work.style.setProperty(`--${k}`, v);
  } catch {
    /* ignore a bad saved layout */
  }
  for (const bar of document.querySelectorAll<HTMLElement>(".splitter")) {
    const which = bar.dataset.split === "left" ? "left" : "middle";
    const pane = document.getElementById(which);
    if (!pane) continue;
    bar.addEventListener("pointerdown", (down) => {
      down.preventDefault();
      bar.setPointerCapture(down.pointerId);
      bar.classList.add("dragging");
      document.body.classList.add("resizing");
      const start = pane.getBoundingClientRect().width;
      let frame = 0;
      const move = (e: PointerEvent): void => {
        const max = work.getBoundingClientRect().width - 480;
        const w = Math.max(180, Math.min(max, start + e.clientX - down.clientX));
        work.style.setProperty(`--${which}`, `${Math.round(w)}px`);
        cancelAnimationFrame(frame);
        frame = requestAnimationFrame(notifyResize);
      };
      const up = (): void => {
        bar.removeEventListener("pointermove", move);
        bar.classList.remove("dragging");
        document.body.classList.remove("resizing");
        const saved = {
          left: work.style.getPropertyValue("--left"),
          middle: work.style.getPropertyValue("--middle"),
        };
        try {
          localStorage.setItem(LAYOUT_KEY, JSON.stringify(saved));
        } catch {
          /* storage may be off */
        }
        notifyResize();
      };
      bar.addEventListener("pointermove", move);
      bar.addEventListener("pointerup", up, { once: true });
      bar.addEventListener("pointercancel", up, { once: true });
    });
    bar.addEventListener("dblclick", () => {
      work.style.removeProperty(`--${which}`);
      notifyResize();
    });
  }
}

export function mountLayout(): void {
  mountTabs();
  mountSplitters();
  showTab("viewer"); // the 3D view first, always (the tab is not remembered across loads)
}
