// Timeline zoom and fault filters. Everything on the page reads without
// this script; it only shows the controls and acts on them.
(function () {
  'use strict';
  document.documentElement.setAttribute('data-js', 'on');
  document.querySelectorAll('.controls').forEach(function (c) { c.hidden = false; });

  var svg = document.querySelector('svg.timeline');
  if (svg) {
    var width = parseFloat(svg.getAttribute('width'));
    var zoom = 1;
    var setZoom = function (z) {
      zoom = Math.min(40, Math.max(0.05, z));
      svg.setAttribute('width', (width * zoom).toFixed(0));
      svg.style.setProperty('--z', zoom);
    };
    document.querySelectorAll('#timeline [data-zoom]').forEach(function (b) {
      b.addEventListener('click', function () {
        var f = parseFloat(b.getAttribute('data-zoom'));
        var box = svg.parentNode;
        setZoom(f === 0 ? box.clientWidth / width : zoom * f);
      });
    });
  }

  var signal = document.getElementById('fault-signal');
  var outcome = document.getElementById('fault-outcome');
  var count = document.getElementById('fault-count');
  var rows = document.querySelectorAll('table.faults tbody tr');
  var filter = function () {
    var s = signal.value.trim().toLowerCase();
    var o = outcome.value.replace(' ', '-');
    var shown = 0;
    rows.forEach(function (r) {
      var names = r.getAttribute('data-signals').toLowerCase().split('+');
      var ok = (!s || names.indexOf(s) >= 0 || r.cells[0].textContent.toLowerCase().indexOf(s) >= 0) &&
        (!o || r.classList.contains(o));
      r.hidden = !ok;
      if (ok) shown++;
    });
    count.textContent = shown + ' of ' + rows.length + ' rows';
  };
  if (signal && outcome && count) {
    signal.addEventListener('input', filter);
    outcome.addEventListener('change', filter);
    filter();
  }
})();
