// objrecall web page: browse the catalog, recall an object from a description, show its grasp.
// Every catalog string (names come from scraped pages) goes into the DOM through textContent, never
// innerHTML, so a product called "<script>..." is shown as text.
"use strict";

const PAGE = 25;
let offset = 0;
let total = 0;
let pending = 0;

function el(tag, text, cls) {
  const node = document.createElement(tag);
  if (text !== undefined && text !== null) node.textContent = String(text);
  if (cls) node.className = cls;
  return node;
}

function fmt(value) {
  if (value === null || value === undefined) return "?";
  if (typeof value === "number") return Number.isInteger(value) ? String(value) : value.toFixed(2);
  return String(value);
}

function busy(delta) {
  pending += delta;
  document.body.dataset.state = pending > 0 ? "loading" : "idle";
}

async function api(path, body, token) {
  const headers = { "Content-Type": "application/json" };
  if (token) headers.Authorization = `Bearer ${token}`;
  const init = body === undefined ? {} : { method: "POST", headers, body: JSON.stringify(body) };
  busy(1);
  try {
    const response = await fetch(path, init);
    let data = null;
    try { data = await response.json(); } catch (e) { data = null; }
    if (!response.ok) {
      const detail = data && data.detail ? data.detail : response.statusText;
      throw new Error(`${response.status}: ${detail}`);
    }
    return data;
  } finally {
    busy(-1);
  }
}

function setStatus(id, text, isError) {
  const node = document.getElementById(id);
  node.textContent = text || "";
  node.classList.toggle("error", Boolean(isError));
}

// ------------------------------------------------------------------------------------------ catalog
async function loadCatalog() {
  const body = document.querySelector("#catalog tbody");
  try {
    const page = await api(`/objects?limit=${PAGE}&offset=${offset}`);
    total = page.total;
    body.replaceChildren();
    for (const obj of page.items) {
      const row = el("tr");
      row.dataset.name = obj.name;
      row.append(el("td", obj.name, "name"));
      for (const f of ["a_cm", "b_cm", "c_cm", "mass_g"]) row.append(el("td", fmt(obj[f]), "num"));
      for (const f of ["shape", "material", "texture", "fragility", "rigidity"]) row.append(el("td", fmt(obj[f])));
      body.append(row);
    }
    const last = Math.min(offset + PAGE, total);
    document.getElementById("page-info").textContent =
      total ? `${offset + 1}-${last} of ${total} objects` : "the catalog is empty";
    document.getElementById("prev").disabled = offset === 0;
    document.getElementById("next").disabled = offset + PAGE >= total;
    setStatus("catalog-status", "");
  } catch (err) {
    setStatus("catalog-status", `Could not load the catalog: ${err.message}`, true);
  }
}

// ------------------------------------------------------------------------------------------- recall
function contributionCell(contributions) {
  const cell = el("td");
  const entries = Object.entries(contributions || {}).sort((a, b) => b[1] - a[1]);
  if (!entries.length) cell.textContent = "(named in the description)";
  for (const [feature, value] of entries) {
    const item = el("span", `${feature} ${fmt(value)}`, "contrib");
    item.dataset.feature = feature;
    const bar = el("span", null, "bar");
    bar.style.width = `${Math.min(Math.max(value, 0), 10) * 0.6}rem`;
    item.append(bar);
    cell.append(item);
  }
  return cell;
}

function showGrasp(plan) {
  const box = document.getElementById("grasp");
  box.replaceChildren();
  if (!plan || !plan.plans || !plan.plans.length) {
    box.append(el("p", "no grasp plan"));
    return;
  }
  const best = plan.plans[0];
  const head = el("p");
  head.id = "grasp-type";
  head.dataset.grasp = best.grasp_type;
  head.append(el("strong", best.grasp_type));
  head.append(document.createTextNode(
    ` (${best.family}) for ${plan.object}: across ${best.grasped_dim}, aperture ${fmt(best.aperture_cm)} cm, ` +
    `${best.approach} approach, grip force ${fmt(best.grip_force_n)} N`));
  box.append(head);
  if (plan.recalled && plan.recalled.why) box.append(el("p", plan.recalled.why, "meta"));
  const list = el("ul");
  for (const line of best.rationale || []) list.append(el("li", line));
  box.append(list);
  if (plan.plans.length > 1) {
    box.append(el("p", "Alternatives: " + plan.plans.slice(1).map((p) => p.grasp_type).join(", "), "meta"));
  }
  showValidation(box, plan);
}

// The latest MuJoCo validation of the object (first vs validated choice) and a render of the grasp.
function showValidation(box, plan) {
  const v = plan.validation;
  const line = el("p");
  line.id = "grasp-validation";
  let shown = plan.plans[0].grasp_type;
  if (!v) {
    line.textContent = "Not validated in simulation with this hand yet (objrecall grasp validate); the render shows the planned grasp.";
  } else {
    const first = `First choice ${v.first} ` + (v.first_holds ? "holds in simulation" : `fails in simulation (${v.first_reason})`);
    const validated = v.validated ? (v.differs ? `; validated choice: ${v.validated}` : "") : `; none of ${v.candidates} candidates holds`;
    line.textContent = first + validated + ".";
    if (v.validated) shown = v.validated;
  }
  box.append(line);
  const img = document.createElement("img");
  img.id = "grasp-render";
  img.alt = `${plan.object}: ${shown} (simulated)`;
  img.src = `/grasp/render?object=${encodeURIComponent(plan.object)}&grasp_type=${encodeURIComponent(shown)}`;
  img.width = 480;
  img.height = 360;
  img.loading = "lazy";
  box.append(img);
}

async function runRecall(text) {
  const result = document.getElementById("recall-result");
  const top = Number(document.getElementById("top").value) || 5;
  const metric = document.getElementById("metric").value;
  const featuresOnly = document.getElementById("features-only").checked;
  const lookup = document.getElementById("lookup").checked;
  const lookupSummary = document.getElementById("lookup-summary");
  lookupSummary.hidden = true;
  setStatus("recall-status", lookup ? "Recalling, and asking the stores if the catalog does not know it..." : "Recalling...");
  try {
    const request = { text, top, metric: metric || null, features_only: featuresOnly };
    let answer;
    if (lookup) {
      const looked = await api("/recall/lookup", request, document.getElementById("token").value.trim());
      answer = looked.result;
      lookupSummary.textContent = looked.looked_up ? `Lookup: ${looked.message}` : "Lookup not needed: the catalog knows it.";
      lookupSummary.dataset.found = String(looked.found);
      lookupSummary.hidden = false;
    } else {
      answer = await api("/recall", request);
    }
    const body = document.querySelector("#matches tbody");
    body.replaceChildren();
    answer.matches.forEach((m, i) => {
      const row = el("tr");
      row.dataset.name = m.name;
      row.append(el("td", i + 1, "num"));
      const name = el("td", m.name, "name");
      if (m.matched_by_name) name.append(el("span", "named", "named"));
      row.append(name);
      row.append(el("td", fmt(m.score), "num"));
      row.append(contributionCell(m.contributions));
      row.append(el("td", m.name_part ? `-${fmt(m.name_part)}` : "", "num"));
      row.append(el("td", m.vague_part ? `+${fmt(m.vague_part)}` : "", "num"));
      body.append(row);
    });
    const summary = document.getElementById("recall-summary");
    const notIn = answer.not_in_catalog && answer.described;
    if (!answer.matches.length) {
      summary.textContent = notIn
        ? `Not in the catalog: no ${answer.described.noun} (kind: ${answer.described.kind}), and no feature to compare.`
        : "The description states no feature the catalog knows and names no object.";
      document.getElementById("grasp").replaceChildren();
    } else {
      summary.replaceChildren();
      const best = el("strong", answer.matches[0].name);
      best.id = "top-match";
      // the verdict line is the recall's own (recall.openset.verdict): the same words as the CLI's
      if (notIn) {
        const verdict = el("strong", "Not in the catalog");
        verdict.id = "not-in-catalog";
        summary.append(verdict, ". Physically closest: ", best, ". ", answer.verdict.text);
      } else {
        summary.append("Best match: ", best, `. ${answer.verdict.text}`);
      }
      const plan = await api("/grasp/plan", answer.open_set ? { text } : { name: answer.matches[0].name });
      showGrasp(plan);
    }
    result.hidden = false;
    setStatus("recall-status", "");
  } catch (err) {
    setStatus("recall-status", `Recall failed: ${err.message}`, true);
  }
}

// -------------------------------------------------------------------------------------------- start
async function showVersion() {
  try {
    const v = await api("/version");
    document.getElementById("version").textContent =
      `objrecall ${v.objrecall}, ${v.catalog.objects} objects in the catalog`;
  } catch (err) {
    setStatus("catalog-status", `The service is not ready: ${err.message}`, true);
  }
}

document.addEventListener("DOMContentLoaded", () => {
  document.getElementById("prev").addEventListener("click", () => { offset = Math.max(0, offset - PAGE); loadCatalog(); });
  document.getElementById("next").addEventListener("click", () => { offset += PAGE; loadCatalog(); });
  document.getElementById("recall-form").addEventListener("submit", (event) => {
    event.preventDefault();
    const text = document.getElementById("q").value.trim();
    if (!text) { setStatus("recall-status", "Type a description first.", true); return; }
    const url = new URL(window.location.href);
    url.searchParams.set("q", text);
    window.history.replaceState(null, "", url);
    runRecall(text);
  });
  const params = new URLSearchParams(window.location.search);
  const tasks = [showVersion(), loadCatalog()];
  const q = params.get("q");
  if (q) {
    document.getElementById("q").value = q;
    tasks.push(runRecall(q));
  }
  Promise.all(tasks).finally(() => { document.body.dataset.ready = "true"; });
});
