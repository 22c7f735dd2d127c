// The charts drawn with Observable Plot, in one chunk the page loads once it has asked for its
// first results (main.ts `plots`): Plot and d3 are most of the page's own JavaScript, and the
// numbers need none of them.
export { airtimeTable, airtimeVsPayloadChart } from './airtime';
export { boxplotChart, type BoxRow } from './boxplot';
export { errorChart, errorChartData } from './errorOverTime';
export { linkBudgetCharts } from './linkBudget';
export { p75BySfChart } from './p75BySf';
export { sfPlanWords, swarmCharts } from './swarm';
export { warmUps } from './warmUp';
