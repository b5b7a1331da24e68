"""The page's style sheet: one column that fits any screen, tables that scroll in their box.

No external resource (no fonts, no images, no ``url(``): the page works offline.
Below 800 px the mechanism's panels stack; below 640 px margins and fonts shrink.
The player sticks to the top of the window from the mechanism to the end of the
plots, so the angle, the controls and one cursor-synced curve stay in view.
"""

PAGE_CSS = """
:root{--player-h:0px}
*{box-sizing:border-box}
html{-webkit-text-size-adjust:100%}
body{margin:0;background:#f4f5f7;color:#1d2330;font:15px/1.45 system-ui,-apple-system,
'Segoe UI',Roboto,sans-serif;overflow-wrap:break-word}
main{max-width:1320px;margin:0 auto;padding:18px 26px 40px;background:#fff;
box-shadow:0 0 12px rgba(0,0,0,.06)}
h1{font-size:24px;margin:6px 0 2px;line-height:1.2}
h2{font-size:19px;border-bottom:2px solid #e3e6ea;padding-bottom:4px;margin:30px 0 10px}
h3{font-size:16px;margin:0 0 2px}
section,.plot-box,.stage{scroll-margin-top:calc(var(--player-h) + 8px)}
.sub{margin:0;color:#445}.meta{color:#556;font-size:13px;margin:6px 0}
nav{font-size:13px;margin:10px 0 0;padding:8px 10px;background:#f1f3f6;border-radius:6px}
nav a{color:#1a5fb4;text-decoration:none}nav a:hover{text-decoration:underline}
details.config pre{background:#f7f7f9;border:1px solid #e3e3e8;padding:10px;font-size:12.5px;
max-height:340px;overflow:auto}
summary{cursor:pointer;color:#1a5fb4}
.table-wrap{max-width:100%;overflow-x:auto;-webkit-overflow-scrolling:touch;margin:8px 0}
table{border-collapse:collapse;font-size:13.5px}
th,td{border-bottom:1px solid #e6e8eb;padding:5px 10px;text-align:left;vertical-align:top}
th{background:#f1f3f6;white-space:nowrap}
td.num,th.num{text-align:right;font-variant-numeric:tabular-nums;white-space:nowrap}
td.q{min-width:14em;max-width:30em}td.q .label{display:block;font-weight:600}
#summary-table td.q,#summary-table th:first-child{position:sticky;left:0;z-index:1;
background:#fff;box-shadow:1px 0 0 #e6e8eb}
#summary-table th:first-child{background:#f1f3f6}
#summary-table tr.disagree td.q{background:#fff3f2}
td.q .def{display:block;color:#556;font-size:12px}
td.src{min-width:12em;max-width:22em;font-size:12.5px;color:#445}
.unit{color:#445}
tr.agree td.diff .mark{color:#1e6b30}tr.disagree td.diff .mark{color:#a3221a;font-weight:700}
tr.disagree td.diff{background:#fff3f2}
.hint,.caption,.heading{color:#556;font-size:13px}
.heading{margin:0 0 4px}
ul#checks-list{list-style:none;padding:0}
li.check{margin:6px 0;padding:7px 10px;border-left:5px solid #999;background:#fafafa}
li.ok{border-color:#2e9d4a}li.note{border-color:#3b78c4;border-left-style:double}
li.warning{border-color:#e0a100;border-left-style:dashed;background:#fffaf0}
li.error{border-color:#c62828;border-left-width:8px;background:#fff3f2}
.badge{display:inline-block;min-width:72px;font-size:11px;font-weight:700;letter-spacing:.04em}
li.ok .badge{color:#1e6b30}li.note .badge{color:#2b5d9b}li.warning .badge{color:#7d5700}
li.error .badge{color:#a3221a}
.player{position:sticky;top:0;z-index:30;contain:layout paint;background:#fff;
border-bottom:1px solid #d5d9e0;box-shadow:0 3px 8px rgba(0,0,0,.07);padding:6px 0 4px;
margin:0 0 8px}
.controls{display:flex;align-items:center;gap:6px 8px;flex-wrap:wrap}
.controls button,.controls select,.mini select{font-size:14px;padding:3px 9px;
border:1px solid #b8bec8;border-radius:5px;background:#f6f7f9;cursor:pointer;color:#1d2330}
#play-button{min-width:6.2em}
#angle-slider{flex:1 1 260px;min-width:140px}
.angle input{width:5.2em;font-size:14px;padding:2px 4px;font-variant-numeric:tabular-nums}
.angle,.speed{font-size:14px;white-space:nowrap}
.mini{display:grid;grid-template-columns:minmax(0,auto) minmax(0,1fr);gap:2px 10px;
align-items:center;margin-top:4px}
.mini select{font-size:12px;padding:1px 4px;max-width:100%}
#mini-value{display:block;height:1.5em;font-size:12.5px;font-variant-numeric:tabular-nums;
color:#223;white-space:nowrap;overflow:hidden;text-overflow:ellipsis;contain:strict}
.mini-plot{grid-column:1 / -1;position:relative;overflow:hidden}
#mini-svg{width:100%;height:92px;display:block;will-change:transform}
#mini-cursor{position:absolute;left:0;top:0;width:0;border-left:1.5px dashed #222;
will-change:transform;pointer-events:none}
#mini-dot{position:absolute;left:-3.5px;top:-3.5px;width:7px;height:7px;border-radius:50%;
background:#222;will-change:transform;pointer-events:none}
#mini-svg .tick{font-size:10px;fill:#556}
.readouts{display:flex;flex-wrap:wrap;gap:4px 18px;font-size:13px;color:#334;margin:6px 0}
.ro-label{color:#667}.ro-value{display:inline-block;min-width:6.5ch;text-align:right;
font-weight:600;font-variant-numeric:tabular-nums}
.mech-row{display:flex;flex-wrap:wrap;gap:12px;align-items:flex-start}
.mpanel{flex:0 0 auto;min-width:0;position:relative;contain:layout paint}
.mtitle{font-size:13px;color:#223;margin:0 0 2px;line-height:1.3}
.mstate{font-size:12.5px;color:#223;margin:0 0 2px;font-variant-numeric:tabular-nums;
min-height:2.6em;contain:layout paint}
.mstack{position:relative;touch-action:pan-y}
.msvg{display:block;max-width:100%;background:#fff}
.msvg.anim{position:absolute;left:0;top:0;background:none;pointer-events:none;
will-change:transform}
.mpanel-3d .mstack{cursor:grab}.mpanel-3d .msvg{background:#fbfbfc}
.mpanel-3d .msvg.anim{background:none}
.mhint{position:absolute;right:6px;bottom:4px;font-size:11px;color:#889}
.msvg .tick{font-size:10px;fill:#556}.msvg .atitle{font-size:11.5px;fill:#334}
.msvg .mlabel{font-variant-numeric:tabular-nums}
.mlegend{display:flex;flex-wrap:wrap;gap:2px 6px;margin:6px 0 0;font-size:12.5px}
.mlegend .li{display:inline-flex;align-items:center;gap:4px;border:0;background:none;
padding:2px 4px;cursor:pointer;color:#223;font:inherit;text-align:left}
.mlegend .li.off{opacity:.4;text-decoration:line-through}
.mlegend .sw{flex:0 0 26px}
.plot{width:100%;position:relative}
.plot-box{margin:18px 0 26px}
.plot-tools{display:flex;flex-wrap:wrap;gap:4px 14px;font-size:13px;margin:0 0 2px}
.plot-tools a{color:#1a5fb4}
.failed{color:#a3221a;font-weight:600}
details.ext{margin:4px 0}details.ext table{font-size:12.5px}
.cursor{position:absolute;left:0;top:0;width:0;border-left:1.5px dashed rgba(20,20,20,.6);
pointer-events:none;display:none;will-change:transform}
footer{margin-top:30px;color:#778;font-size:12px}
@media (max-width:800px){.mpanel{width:100% !important}}
@media (max-width:640px){
main{padding:10px 10px 30px}
h1{font-size:20px}h2{font-size:17px;margin-top:22px}
body{font-size:14px}
.controls button,.controls select{padding:3px 7px}
#play-button{min-width:5.4em}
#angle-slider{flex-basis:100%;order:9}
#mini-svg{height:64px}
.mini{grid-template-columns:minmax(0,1fr) 11.5em}
.mini select{font-size:11.5px}#mini-value{font-size:12px}
.speed-word{display:none}
td.q{min-width:10em;max-width:13em}
}
"""
