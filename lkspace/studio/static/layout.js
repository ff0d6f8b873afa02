// Narrow screens (phones): the view on top, one panel below it, chosen by tabs (style.css shows
// the tabs only under 700 px; on a desktop the three columns stay as they are).
const $ = (id) => document.getElementById(id);

export function installLayout() {
  const tabs = document.createElement('nav');
  tabs.id = 'tabs';
  tabs.innerHTML = '<button data-panel="left">design</button><button data-panel="right">read</button><button data-panel="catalog" hidden>catalog</button>';
  document.body.append(tabs);
  const show = (panel) => {
    document.body.dataset.panel = panel;
    for (const b of tabs.children) b.classList.toggle('active', b.dataset.panel === panel);
  };
  tabs.onclick = (ev) => { const b = ev.target.closest('button'); if (b) show(b.dataset.panel); };
  const catalogTab = tabs.querySelector('[data-panel="catalog"]');
  new MutationObserver(() => { catalogTab.hidden = $('catalog').hidden; }).observe($('catalog'), { attributes: true, attributeFilter: ['hidden'] });
  catalogTab.hidden = $('catalog').hidden;
  show('left');
}
