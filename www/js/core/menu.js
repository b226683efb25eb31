// The top bar's menu on narrow screens: below the CSS breakpoint the other views, Share and
// Export fold behind one Menu button (a real button with aria-expanded, so keyboards and screen
// readers reach them). The menu overlays the page instead of pushing the canvas down. On wide
// screens the button is hidden by CSS and the items sit in the bar.

const toggle = document.getElementById('menu-toggle');
const menu = document.getElementById('topbar-menu');

if (toggle && menu) {
  const bar = toggle.closest('.topbar');
  const setOpen = (open) => {
    toggle.setAttribute('aria-expanded', String(open));
    bar.classList.toggle('menu-open', open);
  };
  const isOpen = () => toggle.getAttribute('aria-expanded') === 'true';

  toggle.addEventListener('click', () => {
    setOpen(!isOpen());
    if (isOpen()) menu.querySelector('a, button')?.focus();
  });
  // Choosing an item (a link, Share…, Export…) closes the menu; its dialog then has the screen. An
  // item marked data-menu-stays (Copy link, which answers "Link copied" in place) keeps it open.
  menu.addEventListener('click', (e) => {
    const item = e.target.closest('a, button');
    if (item && !item.hasAttribute('data-menu-stays')) setOpen(false);
  });
  document.addEventListener('keydown', (e) => {
    if (e.key === 'Escape' && isOpen()) {
      setOpen(false);
      toggle.focus();
    }
  });
  document.addEventListener('pointerdown', (e) => {
    if (isOpen() && !menu.contains(e.target) && !toggle.contains(e.target)) setOpen(false);
  });
  // Keyboard focus leaving the menu closes it (Tab past the last item).
  menu.addEventListener('focusout', (e) => {
    if (isOpen() && e.relatedTarget && !menu.contains(e.relatedTarget) && e.relatedTarget !== toggle) setOpen(false);
  });
}
