window.addEventListener('load', () => {
  const images = [...document.images];
  document.body.dataset.images = images.length;
  document.body.dataset.imagesLoaded = images.filter(i => i.complete && i.naturalWidth > 0).length;
  document.body.dataset.tables = document.querySelectorAll('table').length;
  document.body.dataset.svgs = document.querySelectorAll('figure svg').length;
  document.body.dataset.legends = document.querySelectorAll('.legend[data-palette]').length;
});
